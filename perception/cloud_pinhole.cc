#include "perception/cloud_pinhole.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace sortcell::perception {
namespace {

// Fits pixel = f * ratio + c over the samples, one axis at a time (the normal equations of a line).
struct LineFit {
  double n = 0, sx = 0, sxx = 0, sy = 0, sxy = 0, lo = 1e9, hi = -1e9;
  void Add(double ratio, double pixel) {
    n += 1, sx += ratio, sxx += ratio * ratio, sy += pixel, sxy += ratio * pixel;
    lo = std::min(lo, pixel), hi = std::max(hi, pixel);
  }
  Eigen::Vector2d Solve() const {
    Eigen::Matrix2d a;
    a << sxx, sx, sx, n;
    return a.ldlt().solve(Eigen::Vector2d(sxy, sy));
  }
};

}  // namespace

Pinhole FitPinhole(const Cloud& cloud, int stride) {
  if (!cloud.isOrganized()) throw std::invalid_argument("FitPinhole: the cloud is not organized");
  if (stride < 1) throw std::invalid_argument("FitPinhole: stride must be >= 1");
  LineFit u_fit, v_fit;
  for (int v = 0; v < static_cast<int>(cloud.height); v += stride) {
    for (int u = 0; u < static_cast<int>(cloud.width); u += stride) {
      const PointT& p = cloud.at(u, v);
      if (!std::isfinite(p.z) || p.z <= 0) continue;
      u_fit.Add(p.x / p.z, u);
      v_fit.Add(p.y / p.z, v);
    }
  }
  if (u_fit.n < 100 || u_fit.hi - u_fit.lo < 0.1 * cloud.width || v_fit.hi - v_fit.lo < 0.1 * cloud.height) {
    throw std::invalid_argument("FitPinhole: too few valid points to fit the camera's pinhole");
  }
  const Eigen::Vector2d fu = u_fit.Solve(), fv = v_fit.Solve();
  return {fu(0), fv(0), fu(1), fv(1)};
}

}  // namespace sortcell::perception
