#include "perception/feature_scaling.h"

#include <stdexcept>
#include <string>

namespace sortcell::perception {

FeatureScaling FeatureScaling::Fit(const Eigen::MatrixXf& samples) {
  if (samples.rows() == 0) throw std::invalid_argument("feature scaling: no training samples");
  if (!samples.allFinite()) throw std::invalid_argument("feature scaling: non-finite feature values");
  FeatureScaling s;
  s.min = samples.colwise().minCoeff().transpose();
  const Eigen::VectorXf range = samples.colwise().maxCoeff().transpose() - s.min;
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
