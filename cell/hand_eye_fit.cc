#include "cell/hand_eye_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sortcell::cell {
namespace {

// The rigid fit over the sightings marked in `use`; nullopt if they are too few or do not spread out.
std::optional<Eigen::Isometry3d> Fit(const std::vector<Eigen::Vector3d>& p_W, const std::vector<Eigen::Vector3d>& p_C,
                                     const std::vector<bool>& use, const HandEyeFitParams& params) {
  const int n = static_cast<int>(std::count(use.begin(), use.end(), true));
  if (n < std::max(3, params.min_inliers)) return std::nullopt;
  Eigen::Matrix3Xd from(3, n), to(3, n);
  for (size_t i = 0, k = 0; i < use.size(); ++i) {
    if (!use[i]) continue;
    from.col(k) = p_C[i];
    to.col(k++) = p_W[i];
  }
  const Eigen::Matrix3Xd centred = from.colwise() - from.rowwise().mean();
  const Eigen::Vector3d spread = Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues() / std::sqrt(n);
  if (spread(1) < params.min_spread_m) return std::nullopt;
  return Eigen::Isometry3d(Eigen::umeyama(from, to, false));
}

}  // namespace

std::optional<HandEyeFit> FitCameraPose(const std::vector<Eigen::Vector3d>& p_W,
                                        const std::vector<Eigen::Vector3d>& p_C, const HandEyeFitParams& params) {
  if (p_W.size() != p_C.size()) throw std::invalid_argument("FitCameraPose: p_W and p_C differ in size");
  HandEyeFit fit;
  fit.inlier.assign(p_W.size(), true);
  // Refit without the outliers until the inlier set stops changing (a few passes at most; the last
  // pass's fit stands).
  for (int pass = 0; pass < 5; ++pass) {
    const auto X_WC = Fit(p_W, p_C, fit.inlier, params);
    if (!X_WC) return std::nullopt;
    fit.X_WC = *X_WC;
    fit.residual_m.resize(p_W.size());
    std::vector<double> kept;
    for (size_t i = 0; i < p_W.size(); ++i) {
      fit.residual_m[i] = (fit.X_WC * p_C[i] - p_W[i]).norm();
      if (fit.inlier[i]) kept.push_back(fit.residual_m[i]);
    }
    std::nth_element(kept.begin(), kept.begin() + kept.size() / 2, kept.end());
    const double limit = std::max(params.min_outlier_m, params.outlier_sigmas * 1.4826 * kept[kept.size() / 2]);
    std::vector<bool> inlier(p_W.size());
    for (size_t i = 0; i < p_W.size(); ++i) inlier[i] = fit.residual_m[i] <= limit;
    if (inlier == fit.inlier || pass == 4) break;
    fit.inlier = inlier;
  }
  fit.inliers = static_cast<int>(std::count(fit.inlier.begin(), fit.inlier.end(), true));
  if (fit.inliers < params.min_inliers) return std::nullopt;
  double sum = 0;
  for (size_t i = 0; i < p_W.size(); ++i) {
    if (!fit.inlier[i]) continue;
    sum += fit.residual_m[i] * fit.residual_m[i];
    fit.max_m = std::max(fit.max_m, fit.residual_m[i]);
  }
  fit.rms_m = std::sqrt(sum / fit.inliers);
  return fit;
}

}  // namespace sortcell::cell
