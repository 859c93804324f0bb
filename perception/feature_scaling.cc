#include "perception/feature_scaling.h"

#include <stdexcept>
#include <string>

namespace sortcell::perception {

namespace {

void CheckBlocks(const std::vector<FeatureBlock>& blocks, Eigen::Index features) {
  Eigen::Index next = 0;
  for (const FeatureBlock& b : blocks) {
    if (b.size <= 0) {
      throw std::invalid_argument("feature scaling: the block at " + std::to_string(b.start) + " has no features");
    }
    if (b.start != next) {
      throw std::invalid_argument("feature scaling: block at " + std::to_string(b.start) + " of " +
                                  std::to_string(b.size) + " features does not follow on at " + std::to_string(next));
    }
    next += b.size;
  }
  if (next != features) {
    throw std::invalid_argument("feature scaling: the blocks cover " + std::to_string(next) + " of " +
                                std::to_string(features) + " features");
  }
}

}  // namespace

FeatureScaling FeatureScaling::Fit(const Eigen::MatrixXf& samples, const std::vector<FeatureBlock>& blocks) {
  if (samples.rows() == 0) throw std::invalid_argument("feature scaling: no training samples");
  if (!samples.allFinite()) throw std::invalid_argument("feature scaling: non-finite feature values");
  FeatureScaling s;
  s.min = samples.colwise().minCoeff().transpose();
  Eigen::VectorXf top = samples.colwise().maxCoeff().transpose();
  if (!blocks.empty()) {
    CheckBlocks(blocks, samples.cols());
    for (const FeatureBlock& b : blocks) {
      s.min.segment(b.start, b.size).setConstant(s.min.segment(b.start, b.size).minCoeff());
      top.segment(b.start, b.size).setConstant(top.segment(b.start, b.size).maxCoeff());
    }
  }
  const Eigen::VectorXf range = top - s.min;
  s.scale = (range.array() > 1e-12f).select(range.array().inverse(), 0.0f);
  return s;
}

Eigen::VectorXf FeatureScaling::Apply(const Eigen::VectorXf& x) const {
  if (x.size() != min.size()) {
    throw std::invalid_argument("feature scaling: a sample has " + std::to_string(x.size()) + " features, expected " +
                                std::to_string(min.size()));
  }
  return ((x - min).array() * scale.array()).cwiseMax(0.0f).cwiseMin(1.0f).matrix();
}

}  // namespace sortcell::perception
