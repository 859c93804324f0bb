#include "perception/svm_classifier.h"

#include <libsvm/svm.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

namespace sortcell::perception {
namespace {

void Quiet(const char*) {}

// libsvm's probability training shuffles with rand(); it is seeded right before, under this lock,
// so that the same data always gives the same model.
std::mutex& LibsvmRandLock() {
  static std::mutex lock;
  return lock;
}

svm_parameter RbfParameter(double C, double gamma, bool probability) {
  svm_parameter p{};
  p.svm_type = C_SVC;
  p.kernel_type = RBF;
  p.gamma = gamma;
  p.C = C;
  p.cache_size = 200;
  p.eps = 1e-3;
  p.shrinking = 1;
  p.probability = probability ? 1 : 0;
  p.nr_weight = 0;
  return p;
}

}  // namespace

// Sparse libsvm rows (index from 1, zeros skipped, -1 terminated) in one block. Outside the anonymous
// namespace: SvmClassifier::Storage holds one, and in a unity build a class member of an anonymous
// namespace's type is flagged (-Wsubobject-linkage) once this file is not the compiler's main file.
struct SvmNodeRows {
  std::vector<svm_node> nodes;
  std::vector<svm_node*> rows;

  explicit SvmNodeRows(const Eigen::MatrixXd& dense) {
    std::vector<size_t> start;
    for (Eigen::Index r = 0; r < dense.rows(); ++r) {
      start.push_back(nodes.size());
      for (Eigen::Index c = 0; c < dense.cols(); ++c) {
        if (dense(r, c) != 0.0) nodes.push_back({static_cast<int>(c) + 1, dense(r, c)});
      }
      nodes.push_back({-1, 0.0});
    }
    for (size_t s : start) rows.push_back(nodes.data() + s);
  }
};

namespace {

std::vector<svm_node> ToNodes(const Eigen::VectorXf& x) {
  std::vector<svm_node> nodes;
  for (Eigen::Index c = 0; c < x.size(); ++c) {
    if (x[c] != 0.0f) nodes.push_back({static_cast<int>(c) + 1, x[c]});
  }
  nodes.push_back({-1, 0.0});
  return nodes;
}

// Fold of each sample: whole groups per fold, groups dealt to folds in a fixed shuffled order.
std::vector<int> GroupFolds(const std::vector<int>& groups, int folds) {
  const std::set<int> distinct(groups.begin(), groups.end());
  std::vector<int> unique(distinct.begin(), distinct.end());
  if (static_cast<int>(unique.size()) < folds) {
    throw std::invalid_argument("SVM training: " + std::to_string(unique.size()) + " groups for " +
                                std::to_string(folds) + "-fold grouped cross-validation");
  }
  std::mt19937_64 rng(0x5eed);
  std::shuffle(unique.begin(), unique.end(), rng);
  std::vector<int> fold(groups.size());
  for (size_t i = 0; i < groups.size(); ++i) {
    fold[i] = static_cast<int>(std::find(unique.begin(), unique.end(), groups[i]) - unique.begin()) % folds;
  }
  return fold;
}

// The true class's one-vs-one margin for one sample: the smallest decision value, signed towards the
// true class, over the pairs it takes part in (libsvm orders pairs (i, j), i < j, by model->label).
// `predicted` gets libsvm's vote (what svm_predict returns), from the same decision values.
double TrueClassMargin(const svm_model* model, const svm_node* x, double y, std::vector<double>& decision,
                       double& predicted) {
  predicted = svm_predict_values(model, x, decision.data());
  const int k = model->nr_class;
  int truth = -1;
  for (int i = 0; i < k; ++i) {
    if (model->label[i] == static_cast<int>(y)) truth = i;
  }
  if (truth < 0) return -1;  // A class the fold's training part did not hold: wrong, fully.
  double margin = std::numeric_limits<double>::infinity();
  for (int i = 0, pair = 0; i < k; ++i) {
    for (int j = i + 1; j < k; ++j, ++pair) {
      if (i == truth) margin = std::min(margin, decision[pair]);
      if (j == truth) margin = std::min(margin, -decision[pair]);
    }
  }
  return margin;
}

// Grouped cross-validation of one (C, gamma): the held-out accuracy, and the held-out samples' mean
// margin clipped at 1 (minus the hinge loss) to tell apart settings of the same accuracy: with few
// samples many settings classify every held-out one right, and the first of them (the smallest C)
// is the least confident.
CvScore CrossValidate(const SvmNodeRows& x, const std::vector<double>& y, const std::vector<int>& fold, int folds,
                      double C, double gamma) {
  const svm_parameter param = RbfParameter(C, gamma, false);
  int correct = 0;
  double margin_sum = 0;
  for (int f = 0; f < folds; ++f) {
    std::vector<svm_node*> train_x;
    std::vector<double> train_y;
    for (size_t i = 0; i < y.size(); ++i) {
      if (fold[i] != f) {
        train_x.push_back(x.rows[i]);
        train_y.push_back(y[i]);
      }
    }
    svm_problem problem{static_cast<int>(train_y.size()), train_y.data(), train_x.data()};
    svm_model* model = svm_train(&problem, &param);
    std::vector<double> decision(static_cast<size_t>(model->nr_class) * (model->nr_class - 1) / 2 + 1);
    for (size_t i = 0; i < y.size(); ++i) {
      if (fold[i] != f) continue;
      double predicted = 0;
      margin_sum += std::min(1.0, TrueClassMargin(model, x.rows[i], y[i], decision, predicted));
      if (predicted == y[i]) ++correct;
    }
    svm_free_and_destroy_model(&model);
  }
  return {C, gamma, static_cast<double>(correct) / y.size(), margin_sum / y.size()};
}

// Refuses training input that cannot make a model.
void CheckTrainingInput(const Eigen::MatrixXf& samples, const std::vector<int>& labels, const std::vector<int>& groups,
                        int classes, const SvmGrid& grid) {
  const size_t n = static_cast<size_t>(samples.rows());
  if (labels.size() != n || groups.size() != n) {
    throw std::invalid_argument("SVM training: " + std::to_string(n) + " samples, " + std::to_string(labels.size()) +
                                " labels, " + std::to_string(groups.size()) + " groups");
  }
  std::set<int> present;
  for (int label : labels) {
    if (label < 0 || label >= classes) {
      throw std::invalid_argument("SVM training: label " + std::to_string(label) + " outside [0, " +
                                  std::to_string(classes) + ")");
    }
    present.insert(label);
  }
  if (present.size() < 2) throw std::invalid_argument("SVM training: the samples hold fewer than two classes");
  if (grid.C.empty() || grid.gamma.empty() || grid.folds < 2) {
    throw std::invalid_argument("SVM training: empty (C, gamma) grid or fewer than 2 folds");
  }
}

// Grouped cross-validation of every (C, gamma) of the grid, on grid.threads threads; in the grid's order.
std::vector<CvScore> GridSearch(const SvmNodeRows& x, const std::vector<double>& y, const std::vector<int>& fold,
                                const SvmGrid& grid) {
  std::vector<CvScore> scores(grid.C.size() * grid.gamma.size());
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k = next++; k < scores.size(); k = next++) {
      const double C = grid.C[k / grid.gamma.size()], gamma = grid.gamma[k % grid.gamma.size()];
      scores[k] = CrossValidate(x, y, fold, grid.folds, C, gamma);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < std::max(1, grid.threads); ++t) threads.emplace_back(worker);
  worker();
  for (auto& thread : threads) thread.join();
  return scores;
}

}  // namespace

// The libsvm model with every array owned by vectors here (svm_model only points into them).
struct SvmClassifier::Storage {
  SvmClassifier::Arrays arrays;
  SvmNodeRows sv{Eigen::MatrixXd()};
  std::vector<double*> coef_rows;
  svm_model model{};

  explicit Storage(SvmClassifier::Arrays a) : arrays(std::move(a)), sv(arrays.sv) {
    model.param = RbfParameter(arrays.C, arrays.gamma, true);
    model.nr_class = static_cast<int>(arrays.label.size());
    model.l = static_cast<int>(arrays.sv.rows());
    model.SV = sv.rows.data();
    for (Eigen::Index k = 0; k < arrays.sv_coef.rows(); ++k) coef_rows.push_back(arrays.sv_coef.row(k).data());
    model.sv_coef = coef_rows.data();
    model.rho = arrays.rho.data();
    model.probA = arrays.probA.data();
    model.probB = arrays.probB.data();
    model.sv_indices = nullptr;
    model.label = arrays.label.data();
    model.nSV = arrays.nSV.data();
    model.free_sv = 0;
  }
};

SvmClassifier::SvmClassifier() = default;
SvmClassifier::SvmClassifier(SvmClassifier&&) noexcept = default;
SvmClassifier& SvmClassifier::operator=(SvmClassifier&&) noexcept = default;
SvmClassifier::~SvmClassifier() = default;

int LinkedLibsvmVersion() { return libsvm_version; }

SvmClassifier SvmClassifier::Train(const Eigen::MatrixXf& samples, const std::vector<int>& labels,
                                   const std::vector<int>& groups, int classes, const SvmGrid& grid,
                                   const std::vector<FeatureBlock>& scaling_blocks) {
  CheckTrainingInput(samples, labels, groups, classes, grid);
  const size_t n = static_cast<size_t>(samples.rows());
  svm_set_print_string_function(&Quiet);

  SvmClassifier result;
  result.classes_ = classes;
  result.scaling_ = FeatureScaling::Fit(samples, scaling_blocks);
  Eigen::MatrixXd scaled(samples.rows(), samples.cols());
  for (Eigen::Index r = 0; r < samples.rows(); ++r) {
    scaled.row(r) = result.scaling_.Apply(samples.row(r).transpose()).cast<double>().transpose();
  }
  const SvmNodeRows x(scaled);
  std::vector<double> y(labels.begin(), labels.end());
  const std::vector<int> fold = GroupFolds(groups, grid.folds);

  result.cv_scores_ = GridSearch(x, y, fold, grid);
  // The best held-out accuracy; among equals, the largest held-out margin.
  const CvScore best =
      *std::max_element(result.cv_scores_.begin(), result.cv_scores_.end(), [](const CvScore& a, const CvScore& b) {
        return a.accuracy < b.accuracy || (a.accuracy == b.accuracy && a.margin < b.margin);
      });

  const svm_parameter param = RbfParameter(best.C, best.gamma, true);
  svm_problem problem{static_cast<int>(n), y.data(), const_cast<svm_node**>(x.rows.data())};
  svm_model* model = nullptr;
  {
    std::lock_guard<std::mutex> lock(LibsvmRandLock());
    std::srand(1);
    model = svm_train(&problem, &param);
  }
  Arrays arrays;
  arrays.C = best.C;
  arrays.gamma = best.gamma;
  const int k = model->nr_class, l = model->l, pairs = k * (k - 1) / 2;
  arrays.label.assign(model->label, model->label + k);
  arrays.nSV.assign(model->nSV, model->nSV + k);
  arrays.rho.assign(model->rho, model->rho + pairs);
  arrays.probA.assign(model->probA, model->probA + pairs);
  arrays.probB.assign(model->probB, model->probB + pairs);
  arrays.sv_coef.resize(k - 1, l);
  arrays.sv = Eigen::MatrixXd::Zero(l, samples.cols());
  for (int i = 0; i < l; ++i) {
    for (int c = 0; c < k - 1; ++c) arrays.sv_coef(c, i) = model->sv_coef[c][i];
    for (const svm_node* node = model->SV[i]; node->index != -1; ++node) arrays.sv(i, node->index - 1) = node->value;
  }
  svm_free_and_destroy_model(&model);
  result.storage_ = std::make_unique<Storage>(std::move(arrays));
  return result;
}

SvmClassifier SvmClassifier::FromArrays(const Arrays& arrays, FeatureScaling scaling, int classes) {
  const int k = static_cast<int>(arrays.label.size());
  const int pairs = k * (k - 1) / 2;
  auto fail = [](const std::string& what) { throw std::invalid_argument("SVM model: " + what); };
  if (k < 2 || k > classes) fail(std::to_string(k) + " SVM classes for " + std::to_string(classes) + " class names");
  if (static_cast<int>(arrays.nSV.size()) != k) fail("nSV has " + std::to_string(arrays.nSV.size()) + " entries");
  if (std::accumulate(arrays.nSV.begin(), arrays.nSV.end(), 0) != arrays.sv.rows()) fail("nSV does not sum to l");
  for (const auto* v : {&arrays.rho, &arrays.probA, &arrays.probB}) {
    if (static_cast<int>(v->size()) != pairs) fail("rho/probA/probB need " + std::to_string(pairs) + " entries");
  }
  for (int label : arrays.label) {
    if (label < 0 || label >= classes) fail("label " + std::to_string(label) + " out of range");
  }
  if (arrays.sv_coef.rows() != k - 1 || arrays.sv_coef.cols() != arrays.sv.rows()) fail("sv_coef has the wrong shape");
  if (arrays.sv.cols() != scaling.min.size() || scaling.scale.size() != scaling.min.size()) {
    fail("support vectors have " + std::to_string(arrays.sv.cols()) + " features, scaling " +
         std::to_string(scaling.min.size()));
  }
  if (!(arrays.C > 0) || !(arrays.gamma > 0)) fail("C and gamma must be positive");
  if (!arrays.sv.allFinite() || !arrays.sv_coef.allFinite()) fail("non-finite support vectors");
  SvmClassifier result;
  result.classes_ = classes;
  result.scaling_ = std::move(scaling);
  result.storage_ = std::make_unique<Storage>(arrays);
  return result;
}

SvmClassifier::Arrays SvmClassifier::ToArrays() const { return storage_->arrays; }
double SvmClassifier::C() const { return storage_->arrays.C; }
double SvmClassifier::gamma() const { return storage_->arrays.gamma; }
int SvmClassifier::support_vectors() const { return static_cast<int>(storage_->arrays.sv.rows()); }

Prediction SvmClassifier::Predict(const Eigen::VectorXf& x) const {
  if (!storage_) throw std::logic_error("SvmClassifier::Predict: the classifier is not trained");
  const std::vector<svm_node> nodes = ToNodes(scaling_.Apply(x));
  const int k = storage_->model.nr_class;
  std::vector<double> by_model_label(k);
  svm_predict_probability(&storage_->model, nodes.data(), by_model_label.data());
  Prediction p;
  p.probabilities.assign(classes_, 0.0);
  for (int i = 0; i < k; ++i) p.probabilities[storage_->arrays.label[i]] = by_model_label[i];
  p.label =
      static_cast<int>(std::max_element(p.probabilities.begin(), p.probabilities.end()) - p.probabilities.begin());
  p.confidence = p.probabilities[p.label];
  return p;
}

}  // namespace sortcell::perception
