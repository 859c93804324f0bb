#pragma once
/// @file
/// Per-feature min-max scaling to [0, 1], fitted on training data only and stored with the model.

#include <Eigen/Core>

namespace sortcell::perception {

struct FeatureScaling {
  Eigen::VectorXf min;    ///< Per feature, over the training rows.
  Eigen::VectorXf scale;  ///< 1 / (max - min); 0 for a constant column (it carries nothing).

  /// Fits on the rows of `samples` (one sample per row).
  /// @throws std::invalid_argument for no rows or non-finite values.
  static FeatureScaling Fit(const Eigen::MatrixXf& samples);

  /// (x - min) * scale, feature by feature, clipped to [0, 1]: a feature outside the range seen in
  /// training (a real sensor's view of a bin no simulated view filled so much) says only "more than any
  /// training view"; unclipped it can outweigh every other feature in the RBF kernel's distance.
  /// @throws std::invalid_argument if x's size differs from the fitted one.
  Eigen::VectorXf Apply(const Eigen::VectorXf& x) const;
};

}  // namespace sortcell::perception
