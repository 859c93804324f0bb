#include "robot/footprint_estimation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace sortcell::robot {
namespace {

struct Extent {
  double low = 0, high = 0;
  double width() const { return high - low; }
  double mid() const { return 0.5 * (low + high); }
};

double Quantile(std::vector<double>& values, double q) {
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(std::lround(q * (values.size() - 1))));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

// The extent of the points' xy projections on `direction`, between the option's quantiles.
Extent ExtentAlong(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector2d& direction,
                   const FootprintOptions& options, std::vector<double>& scratch) {
  scratch.clear();
  for (const auto& p : p_W) scratch.push_back(direction.dot(p.head<2>()));
  Extent e;
  e.low = Quantile(scratch, options.low_quantile);
  e.high = Quantile(scratch, options.high_quantile);
  return e;
}

double YawOf(const Eigen::Vector2d& d) {
  double yaw = std::atan2(d.y(), d.x());
  if (yaw < 0) yaw += M_PI;
  if (yaw >= M_PI) yaw -= M_PI;
  return yaw;
}

// Narrows `width` (the points' extent along `yaw`) to the narrowest extent over half a turn in
// yaw_step steps, and `yaw` to its direction.
void Narrowest(const std::vector<Eigen::Vector3d>& p_W, const FootprintOptions& options, std::vector<double>& scratch,
               double& width, double& yaw) {
  for (double candidate = 0; candidate < M_PI; candidate += options.yaw_step) {
    const double w =
        ExtentAlong(p_W, Eigen::Vector2d(std::cos(candidate), std::sin(candidate)), options, scratch).width();
    if (w < width) {
      width = w;
      yaw = candidate;
    }
  }
}

// The direction of the points' largest spread on the table.
Eigen::Vector2d MajorAxis(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector2d& mean) {
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const auto& p : p_W) {
    const Eigen::Vector2d r = p.head<2>() - mean;
    covariance += r * r.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
  return solver.eigenvectors().col(1);  // Eigenvalues ascend.
}

// Along the long axis `e`, the middle of the stretch where the object stands at its full height (a
// bottle's body, not its neck and cap): the thick part to hold, and near the mass's centre. In 1 cm
// slices; the mean of the points along the axis if no slice is that high.
double MiddleOfFullHeight(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector2d& e, const Extent& length,
                          double table_z, double height) {
  constexpr double kSlice = 0.01, kFull = 0.85;
  const int slices = std::max(1, static_cast<int>(std::ceil(length.width() / kSlice)));
  std::vector<double> top(slices, -INFINITY);
  double mean = 0;
  for (const auto& p : p_W) {
    const double t = e.dot(p.head<2>());
    mean += t;
    const int k = static_cast<int>((t - length.low) / kSlice);
    if (k >= 0 && k < slices) top[k] = std::max(top[k], p.z());
  }
  int first = -1, last = -1;
  for (int k = 0; k < slices; ++k) {
    if (top[k] - table_z < kFull * height) continue;
    if (first < 0) first = k;
    last = k;
  }
  if (first < 0) return mean / static_cast<double>(p_W.size());
  return length.low + kSlice * 0.5 * (first + last + 1);
}

// A long, low object on its side, pinched across its long axis; nullopt if it is not one or too wide.
// `v`: the horizontal line of sight.
std::optional<ObjectFootprint> LyingFootprint(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector2d& mean,
                                              const Eigen::Vector2d& v, double base_z, double height,
                                              const FootprintOptions& options, std::vector<double>& scratch) {
  const Eigen::Vector2d e = MajorAxis(p_W, mean), d(-e.y(), e.x());
  const Extent length = ExtentAlong(p_W, e, options, scratch), across = ExtentAlong(p_W, d, options, scratch);
  if (length.width() < options.lying_elongation * std::max(across.width(), height)) return std::nullopt;
  // A round section is as wide as it is high; the camera may not see its far side.
  const double width = std::max(across.width(), height);
  if (width > options.max_width) return std::nullopt;
  Extent section = across;
  (d.dot(v) >= 0 ? section.high : section.low) += (d.dot(v) >= 0 ? 1 : -1) * (width - across.width());
  ObjectFootprint f;
  f.centre_xy = section.mid() * d + MiddleOfFullHeight(p_W, e, length, base_z, height) * e;
  f.pinch_yaw = YawOf(d);
  f.width = width;
  return f;
}

// Pinched across the line of sight (`u`), its depth along it (`v`) from its nearest point; a prism's top
// face also shows its depth, the way to pinch it turned.
void PinchAcrossView(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector2d& u, const Eigen::Vector2d& v,
                     const Extent& across, bool prism, const FootprintOptions& options, std::vector<double>& scratch,
                     FootprintEstimate& estimate) {
  ObjectFootprint& f = estimate.footprint;
  const Extent along = ExtentAlong(p_W, v, options, scratch);
  const double depth = std::max(along.width(), across.width());
  f.centre_xy = across.mid() * u + (along.low + 0.5 * depth) * v;
  f.pinch_yaw = YawOf(u);
  f.width = across.width();
  if (prism && along.width() <= options.max_width) {
    estimate.turned = f;
    estimate.turned->pinch_yaw = YawOf(v);
    estimate.turned->width = along.width();
  }
}

// Pinched across its narrowest visible direction (`yaw`), centred on what shows; a prism also turned.
void PinchNarrowest(const std::vector<Eigen::Vector3d>& p_W, double yaw, bool prism, const FootprintOptions& options,
                    std::vector<double>& scratch, FootprintEstimate& estimate) {
  ObjectFootprint& f = estimate.footprint;
  const Eigen::Vector2d d(std::cos(yaw), std::sin(yaw)), e(-d.y(), d.x());
  const Extent pinch = ExtentAlong(p_W, d, options, scratch), length = ExtentAlong(p_W, e, options, scratch);
  f.centre_xy = pinch.mid() * d + length.mid() * e;
  f.pinch_yaw = yaw;
  f.width = pinch.width();
  if (prism && length.width() <= options.max_width) {
    estimate.turned = f;
    estimate.turned->pinch_yaw = YawOf(e);
    estimate.turned->width = length.width();
  }
}

}  // namespace

double FullWidthTop(const std::vector<Eigen::Vector3d>& p_W, const ObjectFootprint& object, double fraction) {
  constexpr double kBand = 0.01;
  const int bands = static_cast<int>(std::ceil((object.top_z - object.base_z) / kBand));
  if (bands <= 0) return -INFINITY;
  std::vector<double> reach(bands, 0.0);  // The farthest point from the centre in each band, bottom up.
  for (const Eigen::Vector3d& p : p_W) {
    const int band = static_cast<int>(std::floor((p.z() - object.base_z) / kBand));
    if (band < 0 || band >= bands) continue;
    reach[band] = std::fmax(reach[band], (p.head<2>() - object.centre_xy).norm());
  }
  for (int band = bands - 1; band >= 0; --band) {
    if (reach[band] >= fraction * 0.5 * object.width) return object.base_z + band * kBand;
  }
  return -INFINITY;
}

FootprintEstimate EstimateFootprint(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector3d& p_W_camera,
                                    double table_z, const FootprintOptions& options) {
  if (p_W.size() < 10) {
    throw std::invalid_argument("footprint: expected at least 10 object points, got " + std::to_string(p_W.size()));
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : p_W) mean += p.head<2>();
  mean /= static_cast<double>(p_W.size());
  const Eigen::Vector2d ray = mean - p_W_camera.head<2>();
  // Straight from above there is no hidden side to complete (nor a line of sight to pinch across).
  if (ray.norm() < 0.05) throw std::invalid_argument("footprint: the camera stands right above the object");
  const Eigen::Vector2d v = ray.normalized();  // Horizontal line of sight.
  const Eigen::Vector2d u(-v.y(), v.x());      // Across it.

  std::vector<double> scratch;
  scratch.reserve(p_W.size());
  for (const auto& p : p_W) scratch.push_back(p.z());
  const double top_z = Quantile(scratch, options.high_quantile);
  std::vector<Eigen::Vector3d> top;  // The top face (or cap) of the object.
  for (const auto& p : p_W) {
    if (p.z() >= top_z - options.top_slice) top.push_back(p);
  }

  FootprintEstimate estimate;
  ObjectFootprint& f = estimate.footprint;
  f.top_z = top_z;
  f.base_z = table_z;
  if (const auto lying = LyingFootprint(p_W, mean, v, table_z, top_z - table_z, options, scratch)) {
    estimate.footprint = *lying;
    estimate.footprint.top_z = top_z;
    estimate.footprint.base_z = table_z;
    estimate.lying = true;
    estimate.across_view = false;
    return estimate;
  }
  const Extent across = ExtentAlong(p_W, u, options, scratch);
  // A prism (box, cup) shows its whole footprint in its top face; a tapered object (bottle, ball)
  // shows only a cap there, and its back stays hidden.
  const bool prism =
      top.size() >= 10 && ExtentAlong(top, u, options, scratch).width() >= options.prism_ratio * across.width();
  double narrowest = across.width(), narrowest_yaw = YawOf(u);
  if (prism) Narrowest(p_W, options, scratch, narrowest, narrowest_yaw);
  const bool use_across =
      across.width() <= options.max_width && (!prism || across.width() <= options.across_preference * narrowest);
  if (use_across) {
    PinchAcrossView(p_W, u, v, across, prism, options, scratch, estimate);
  } else {
    // Tapered and too wide across: the narrowest visible direction is all there is.
    if (!prism) Narrowest(p_W, options, scratch, narrowest, narrowest_yaw);
    PinchNarrowest(p_W, narrowest_yaw, prism, options, scratch, estimate);
  }
  estimate.across_view = use_across;
  estimate.prism = prism;
  return estimate;
}

}  // namespace sortcell::robot
