// SVM training, prediction, model file round trip and rejection of foreign or damaged models.
#include "perception/recognition_model.h"
#include "perception/feature_scaling.h"

#include <gtest/gtest.h>

#include "error_of.h"
#include "temp_dir.h"

#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>

namespace sortcell::perception {
namespace {

// Three noisy clusters in descriptor space, ten groups (sequences) per class.
struct Data {
  Eigen::MatrixXf x;
  std::vector<int> y, groups;
};

Data Blobs(int dim, int per_class, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.0f, 0.3f);
  Data d;
  d.x.resize(3 * per_class, dim);
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < per_class; ++i) {
      const int row = c * per_class + i;
      for (int k = 0; k < dim; ++k) d.x(row, k) = (k % 3 == c ? 1.0f : 0.0f) + noise(rng);
      d.y.push_back(c);
      d.groups.push_back(c * 10 + i % 10);
    }
  }
  return d;
}

SvmGrid SmallGrid() {
  SvmGrid g;
  g.C = {1, 16};
  g.gamma = {1.0 / 512, 1.0 / 32};
  return g;
}

RecognitionModel TrainedModel() {
  const Data d = Blobs(308, 30, 1);
  RecognitionModel m;
  m.descriptor = DescriptorKind::kCvfh;
  m.classes = {"bottle", "cup", "ball"};
  m.classifier = SvmClassifier::Train(d.x, d.y, d.groups, 3, SmallGrid());
  m.train_samples = 90;
  return m;
}

using sortcell_test::ErrorOf;

TEST(SvmClassifier, LearnsSeparableClassesWithConfidence) {
  const RecognitionModel m = TrainedModel();
  const Data test = Blobs(308, 10, 2);
  int correct = 0;
  for (int r = 0; r < test.x.rows(); ++r) {
    const Prediction p = m.classifier.Predict(test.x.row(r).transpose());
    correct += p.label == test.y[r];
    EXPECT_GT(p.confidence, 1.0 / 3);
    EXPECT_NEAR(std::accumulate(p.probabilities.begin(), p.probabilities.end(), 0.0), 1.0, 1e-6);
  }
  EXPECT_GE(correct, 28);
  EXPECT_EQ(m.classifier.cv_scores().size(), 4u);
}

TEST(FeatureScaling, ValuesBeyondTheTrainingRangeAreClipped) {
  Eigen::MatrixXf samples(2, 2);
  samples << 0, 10, 2, 20;
  const FeatureScaling s = FeatureScaling::Fit(samples);
  EXPECT_TRUE(s.Apply(Eigen::Vector2f(1, 15)).isApprox(Eigen::Vector2f(0.5f, 0.5f)));
  EXPECT_TRUE(s.Apply(Eigen::Vector2f(4, 5)).isApprox(Eigen::Vector2f(1, 0)));
}

// Scaled block by block, a histogram's bins keep their proportions: a bin that training views seldom fill
// stays small beside the busy ones (per feature, it would weigh as much as any).
TEST(FeatureScaling, ABlockIsScaledAsOne) {
  Eigen::MatrixXf samples(2, 4);
  samples << 0, 1, 5, 0,  //
      8, 3, 10, 2;
  const FeatureScaling s = FeatureScaling::Fit(samples, {{0, 2}, {2, 2}});
  EXPECT_TRUE(s.Apply(Eigen::Vector4f(4, 1, 5, 1)).isApprox(Eigen::Vector4f(0.5f, 0.125f, 0.5f, 0.1f)));
  const FeatureScaling per_feature = FeatureScaling::Fit(samples);
  EXPECT_TRUE(per_feature.Apply(Eigen::Vector4f(4, 1, 5, 1)).isApprox(Eigen::Vector4f(0.5f, 0, 0, 0.5f)));
  // The blocks must cover the features once, in order.
  EXPECT_NE(ErrorOf([&] {
              FeatureScaling::Fit(samples, {{0, 2}, {3, 1}});
            }).find("does not follow on at 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              FeatureScaling::Fit(samples, {{0, 2}, {1, 3}});
            }).find("does not follow on"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { FeatureScaling::Fit(samples, {{0, 3}}); }).find("cover 3 of 4 features"), std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              FeatureScaling::Fit(samples, {{0, 0}, {0, 4}});
            }).find("the block at 0 has no features"),
            std::string::npos);
}

TEST(DescriptorBlocks, EachKindsHistogramsCoverItOnce) {
  for (DescriptorKind kind : {DescriptorKind::kCvfh, DescriptorKind::kColorCvfh, DescriptorKind::kColorCvfhNorm}) {
    const std::vector<FeatureBlock> blocks = DescriptorBlocks(kind);
    int next = 0;
    for (const FeatureBlock& b : blocks) {
      EXPECT_EQ(b.start, next) << DescriptorName(kind);
      next += b.size;
    }
    EXPECT_EQ(next, DescriptorSize(kind)) << DescriptorName(kind);
    EXPECT_EQ(blocks.size(), kind == DescriptorKind::kCvfh ? 5u : 8u);
  }
  EXPECT_EQ(DescriptorBlocks(DescriptorKind::kColorCvfhNorm)[0].size, kHueBins);
  EXPECT_EQ(DescriptorBlocks(DescriptorKind::kColorCvfhNorm)[3].start, kHsvBins);
}

// A real sensor's view can fill one histogram bin far beyond anything seen in training; the rest of the
// view still says what it is.
TEST(SvmClassifier, OneFeatureFarOutsideTheTrainingRangeDoesNotDecide) {
  const RecognitionModel m = TrainedModel();
  const Data test = Blobs(308, 10, 3);
  int correct = 0;
  for (int r = 0; r < test.x.rows(); ++r) {
    Eigen::VectorXf x = test.x.row(r).transpose();
    x[(test.y[r] + 1) % 3] = 1000.0f;  // Another class's feature, a thousand times its usual value.
    correct += m.classifier.Predict(x).label == test.y[r];
  }
  EXPECT_GE(correct, 28);
}

TEST(SvmClassifier, TiesInAccuracyGoToTheLargestHeldOutMargin) {
  // Well separated blobs: every grid point classifies every held-out sample right, so the margin
  // decides, and the chosen point is the one with the largest held-out margin (not the grid's first).
  const RecognitionModel m = TrainedModel();
  const auto& scores = m.classifier.cv_scores();
  double best_margin = -1e9;
  for (const auto& s : scores) {
    EXPECT_EQ(s.accuracy, 1.0);
    EXPECT_LE(s.margin, 1.0);
    best_margin = std::max(best_margin, s.margin);
  }
  int chosen = -1;
  for (size_t k = 0; k < scores.size(); ++k) {
    if (scores[k].C == m.classifier.C() && scores[k].gamma == m.classifier.gamma()) chosen = static_cast<int>(k);
  }
  ASSERT_GE(chosen, 0);
  EXPECT_EQ(scores[chosen].margin, best_margin);
  EXPECT_GT(best_margin, scores[0].margin) << "the grid's first point is not the most confident here";
}

TEST(SvmClassifier, SameDataSameModel) {
  const RecognitionModel a = TrainedModel(), b = TrainedModel();
  const Data test = Blobs(308, 3, 3);
  for (int r = 0; r < test.x.rows(); ++r) {
    EXPECT_EQ(a.classifier.Predict(test.x.row(r).transpose()).probabilities,
              b.classifier.Predict(test.x.row(r).transpose()).probabilities);
  }
}

TEST(SvmClassifier, RejectsTooFewGroupsAndOneClass) {
  const Data d = Blobs(10, 5, 1);
  EXPECT_NE(ErrorOf([&] {
              SvmClassifier::Train(d.x, d.y, std::vector<int>(d.y.size(), 0), 3, SmallGrid());
            }).find("1 groups for 3-fold"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              SvmClassifier::Train(d.x, std::vector<int>(d.y.size(), 1), d.groups, 3, SmallGrid());
            }).find("fewer than two classes"),
            std::string::npos);
}

TEST(RecognitionModel, SaveLoadRoundTripPredictsIdentically) {
  RecognitionModel m = TrainedModel();
  m.label_kind = LabelKind::kInstance;
  m.params.hsv.min_value = 40;
  m.params.cvfh.eps_angle_rad = 0.2;
  m.params.cvfh.min_points = 45;
  const sortcell_test::TempDir dir("recognition_model");
  const auto file = dir / "model.json";
  SaveModel(file, m);
  const RecognitionModel loaded = LoadModel(file, DescriptorKind::kCvfh);
  EXPECT_EQ(loaded.classes, m.classes);
  EXPECT_EQ(loaded.descriptor, DescriptorKind::kCvfh);
  EXPECT_EQ(loaded.label_kind, LabelKind::kInstance);
  EXPECT_TRUE(SameDescriptorParams(loaded.params, m.params));
  EXPECT_FALSE(SameDescriptorParams(loaded.params, DescriptorParams{}));
  EXPECT_EQ(loaded.train_samples, 90);
  EXPECT_DOUBLE_EQ(loaded.classifier.C(), m.classifier.C());
  const Data test = Blobs(308, 5, 4);
  for (int r = 0; r < test.x.rows(); ++r) {
    const Prediction a = m.classifier.Predict(test.x.row(r).transpose());
    const Prediction b = loaded.classifier.Predict(test.x.row(r).transpose());
    EXPECT_EQ(a.label, b.label);
    for (size_t c = 0; c < a.probabilities.size(); ++c) EXPECT_NEAR(a.probabilities[c], b.probabilities[c], 1e-9);
  }
}

TEST(RecognitionModel, RejectsAnotherDescriptor) {
  const sortcell_test::TempDir dir("recognition_model");
  const auto file = dir / "cvfh.json";
  SaveModel(file, TrainedModel());
  EXPECT_EQ(ErrorOf([&] { LoadModel(file, DescriptorKind::kColorCvfhNorm); }),
            "model '" + file.string() + "': trained for descriptor 'cvfh', expected 'color-cvfh-norm'");
}

TEST(RecognitionModel, RejectsDamagedForeignAndMissingFiles) {
  const sortcell_test::TempDir dir("recognition_model");
  const auto file = dir / "damaged.json";
  SaveModel(file, TrainedModel());
  std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);  // Truncated.
  EXPECT_NE(ErrorOf([&] { LoadModel(file); }).find("model '" + file.string() + "'"), std::string::npos);

  const auto foreign = dir / "foreign.json";
  std::ofstream(foreign) << "{\"name\": \"not a model\"}";
  EXPECT_NE(ErrorOf([&] { LoadModel(foreign); }).find("not a SortCell recognition model"), std::string::npos);

  const auto garbage = dir / "garbage.json";
  std::ofstream(garbage) << "\x01\x02 this is not JSON at all";
  EXPECT_NE(ErrorOf([&] { LoadModel(garbage); }).find("model '" + garbage.string() + "'"), std::string::npos);

  EXPECT_EQ(ErrorOf([] { LoadModel("/nonexistent/model.json"); }), "model '/nonexistent/model.json': no such file");
}

TEST(RecognitionModel, RejectsAnotherFormatVersionAndInconsistentArrays) {
  const sortcell_test::TempDir dir("recognition_model");
  const auto file = dir / "version.json";
  SaveModel(file, TrainedModel());
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string version = "\"version\": 2";
  ASSERT_NE(text.find(version), std::string::npos);
  std::string v1 = text;  // A file of before: read (its familiarity, if any, counts colour per point).
  v1.replace(v1.find(version), version.size(), "\"version\": 1");
  std::ofstream(file) << v1;
  EXPECT_EQ(LoadModel(file).classes.size(), 3u);
  std::string v2 = text;
  v2.replace(v2.find(version), version.size(), "\"version\": 3");
  std::ofstream(file) << v2;
  EXPECT_NE(ErrorOf([&] { LoadModel(file); }).find("format version 3, this build reads versions 1 to 2"),
            std::string::npos);

  std::string wrong_kind = text;
  wrong_kind.replace(wrong_kind.find("\"descriptor\": \"cvfh\""), 20, "\"descriptor\": \"color-cvfh\"");
  std::ofstream(file) << wrong_kind;
  EXPECT_NE(ErrorOf([&] { LoadModel(file); }).find("scaling has 308 features, descriptor 'color-cvfh' has 500"),
            std::string::npos);
}

TEST(RecognitionModel, RejectsAnUnknownLabelKind) {
  const sortcell_test::TempDir dir("recognition_model");
  const auto file = dir / "label.json";
  SaveModel(file, TrainedModel());
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string label = "\"label_kind\": \"category\"";
  ASSERT_NE(text.find(label), std::string::npos);
  text.replace(text.find(label), label.size(), "\"label_kind\": \"colour\"");
  std::ofstream(file) << text;
  EXPECT_EQ(ErrorOf([&] { LoadModel(file); }),
            "model '" + file.string() + "': unknown label kind 'colour' (expected category or instance)");
}

TEST(RecognitionModel, AFailedWriteIsAnErrorNamingTheFile) {
  const RecognitionModel m = TrainedModel();
  try {
    SaveModel("/dev/full", m);  // Every write fails with ENOSPC, as on a full disk.
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write model '/dev/full': No space left on device");
  }
  const sortcell_test::TempDir dir("recognition_model");
  const auto nowhere = dir / "gone" / "model.json";
  try {
    SaveModel(nowhere, m);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write model '" + nowhere.string() + "': No such file or directory");
  }
}

TEST(LabelKind, SpellingsRoundTripAndAnUnknownOneIsAClearError) {
  for (LabelKind kind : {LabelKind::kCategory, LabelKind::kInstance}) EXPECT_EQ(ParseLabelKind(ToString(kind)), kind);
  EXPECT_STREQ(ToString(LabelKind::kInstance), "instance");
  EXPECT_EQ(ErrorOf([] { ParseLabelKind("Category"); }),
            "unknown label kind 'Category' (expected category or instance)");
}

TEST(SvmClassifier, LinksDebiansLibsvmNotPclsCopy) {
  EXPECT_EQ(LinkedLibsvmVersion(), 324) << "libpcl_ml embeds libsvm 3.11; -lsvm must come first";
}

}  // namespace
}  // namespace sortcell::perception
