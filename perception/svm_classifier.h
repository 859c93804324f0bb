#pragma once
/// @file
/// Multi-class RBF SVM (libsvm 3.24: one-vs-one C-SVC with Platt/pairwise-coupling probabilities).
///
/// libsvm rather than OpenCV's ml module: it gives a calibrated probability per class (the
/// prediction's confidence), which cv::ml::SVM does not, and it is the SVM the paper's era used.
/// (C, gamma) are chosen by grouped k-fold cross-validation on the training set: whole groups
/// (instances or frame sequences) go to one fold, since neighbouring frames are near-duplicates and
/// a random split would reward memorising. The best held-out accuracy wins; among settings of equal
/// accuracy, the largest held-out margin (CvScore::margin).

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "perception/feature_scaling.h"

namespace sortcell::perception {

struct SvmGrid {
  std::vector<double> C{1, 4, 16, 64, 256, 1024};
  std::vector<double> gamma{1.0 / 512, 1.0 / 128, 1.0 / 32, 1.0 / 8, 1.0 / 2};
  int folds = 3;
  int threads = 2;  ///< Grid points trained in parallel.
};

/// One grid point's grouped cross-validation accuracy and held-out margin.
struct CvScore {
  double C = 0, gamma = 0, accuracy = 0;
  /// Held-out samples' mean one-vs-one margin of their true class, clipped at 1 (1 = every one outside
  /// the margin): the tie-break between settings of the same accuracy.
  double margin = 0;
};

struct Prediction {
  int label = -1;                     ///< Class index, argmax of the probabilities.
  double confidence = 0;              ///< Its probability.
  std::vector<double> probabilities;  ///< Per class index.
};

/// The trained SVM of one descriptor, with its scaling and libsvm model (owned here).
class SvmClassifier {
 public:
  /// Trains on the rows of `samples` (raw descriptors) with class indices `labels` in [0, classes)
  /// and `groups` for the cross-validation (same group, same fold). Fits the scaling (by `scaling_blocks`,
  /// see FeatureScaling::Fit; empty: feature by feature), grid-searches
  /// (C, gamma), then trains the final model with probabilities on all rows. Deterministic.
  /// @throws std::invalid_argument for mismatched sizes, fewer than two classes present, a label out
  ///         of range, or fewer groups than folds.
  static SvmClassifier Train(const Eigen::MatrixXf& samples, const std::vector<int>& labels,
                             const std::vector<int>& groups, int classes, const SvmGrid& grid = {},
                             const std::vector<FeatureBlock>& scaling_blocks = {});

  /// @throws std::invalid_argument if x has the wrong size; std::logic_error if untrained.
  Prediction Predict(const Eigen::VectorXf& x) const;

  int classes() const { return classes_; }
  int features() const { return static_cast<int>(scaling_.min.size()); }
  double C() const;
  double gamma() const;
  const FeatureScaling& scaling() const { return scaling_; }
  const std::vector<CvScore>& cv_scores() const { return cv_scores_; }  ///< Empty for a loaded model.
  int support_vectors() const;

  /// The libsvm model's arrays, for saving and loading (see model_file.h).
  struct Arrays {
    double C = 0, gamma = 0;
    std::vector<int> label, nSV;
    std::vector<double> rho, probA, probB;
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> sv_coef;  ///< (classes - 1) x l.
    Eigen::MatrixXd sv;  ///< l x features, scaled features (dense).
  };
  Arrays ToArrays() const;
  /// @throws std::invalid_argument naming the inconsistent array.
  static SvmClassifier FromArrays(const Arrays& arrays, FeatureScaling scaling, int classes);

  /// An untrained classifier; Predict throws until one is trained or loaded.
  SvmClassifier();
  SvmClassifier(SvmClassifier&&) noexcept;
  SvmClassifier& operator=(SvmClassifier&&) noexcept;
  ~SvmClassifier();

 private:
  struct Storage;
  std::unique_ptr<Storage> storage_;
  FeatureScaling scaling_;
  int classes_ = 0;
  std::vector<CvScore> cv_scores_;
};

/// libsvm in use (3.24 = 324). PCL's libpcl_ml embeds libsvm 3.11 under the same symbol names.
int LinkedLibsvmVersion();

}  // namespace sortcell::perception
