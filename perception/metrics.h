#pragma once
/// @file
/// The paper's recognition metrics (section 3): per class, one-vs-all recall, precision, accuracy and
/// F1 from a confusion matrix; macro averages over the classes; overall accuracy.
/// 0/0 (a class never predicted, or never present) counts as 0, as scikit-learn's zero_division=0.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace sortcell::perception {

/// counts(actual, predicted).
class ConfusionMatrix {
 public:
  /// @throws std::invalid_argument for no classes.
  explicit ConfusionMatrix(std::vector<std::string> classes);
  /// @throws std::invalid_argument for an index out of range.
  void Add(int actual, int predicted, int count = 1);
  const std::vector<std::string>& classes() const { return classes_; }
  const Eigen::MatrixXi& counts() const { return counts_; }
  int total() const { return counts_.sum(); }
  /// Each row as a percentage of its actual count (a row without samples stays 0).
  Eigen::MatrixXd RowPercent() const;

 private:
  std::vector<std::string> classes_;
  Eigen::MatrixXi counts_;
};

struct ClassMetrics {
  int tp = 0, fp = 0, fn = 0, tn = 0;
  double recall = 0, precision = 0, accuracy = 0, f1 = 0;
};

struct RecognitionMetrics {
  std::vector<ClassMetrics> per_class;
  double macro_recall = 0, macro_precision = 0, macro_accuracy = 0, macro_f1 = 0;
  double accuracy = 0;  ///< Overall: trace / total.
};

RecognitionMetrics ComputeMetrics(const ConfusionMatrix& confusion);

}  // namespace sortcell::perception
