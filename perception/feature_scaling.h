#pragma once
/// @file
/// Min-max scaling to [0, 1], feature by feature or histogram block by block, fitted on training data
/// only and stored with the model (as per-feature offsets and factors either way).

#include <Eigen/Core>

#include <vector>

namespace sortcell::perception {

/// Features scaled as one: `size` features from `start` (a histogram of the descriptor).
struct FeatureBlock {
  int start = 0, size = 0;
};

struct FeatureScaling {
  /// Per feature: the least training value of the feature, or of its block when fitted by blocks.
  Eigen::VectorXf min;
  /// Per feature: 1 / (max - min) of the feature or its block; 0 where that range is empty (it carries nothing).
  Eigen::VectorXf scale;

  /// Fits on the rows of `samples` (one sample per row). Without blocks, every feature by its own range.
  /// With blocks (which must cover every feature once, in order), every feature of a block by the block's
  /// range (its least and largest value over all its features): a histogram stays a histogram, and a bin
  /// that training views seldom fill is not stretched to the weight of the busiest one (per feature, the
  /// real sensor's small differences in such bins decided; measured in docs/recognition.md, "Real views").
  /// @throws std::invalid_argument for no rows, non-finite values, or blocks that do not cover the
  ///         features once, in order.
  static FeatureScaling Fit(const Eigen::MatrixXf& samples, const std::vector<FeatureBlock>& blocks = {});

  /// (x - min) * scale, feature by feature, clipped to [0, 1]: a feature outside the range seen in
  /// training (a real sensor's view of a bin no simulated view filled so much) says only "more than any
  /// training view"; unclipped it can outweigh every other feature in the RBF kernel's distance.
  /// @throws std::invalid_argument if x's size differs from the fitted one.
  Eigen::VectorXf Apply(const Eigen::VectorXf& x) const;
};

}  // namespace sortcell::perception
