#include "sim/kinect_noise.h"

#include <spdlog/fmt/fmt.h>

#include <Eigen/Core>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace sortcell::sim {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Eigen::Vector3d BackProject(const CameraIntrinsics& k, int u, int v, double z) {
  return {(u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z};
}

// Every pixel's point (camera frame, m), by row; NaN where the depth is not finite. Each pixel's normal
// uses its four neighbours' points, so each is back-projected once here rather than up to seven times.
std::vector<Eigen::Vector3d> BackProjectAll(const cv::Mat& depth, const CameraIntrinsics& k) {
  std::vector<Eigen::Vector3d> points(depth.total(), Eigen::Vector3d::Constant(kNaN));
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (std::isfinite(z[u])) points[static_cast<size_t>(v) * depth.cols + u] = BackProject(k, u, v, z[u]);
    }
  }
  return points;
}

// Neighbour offsets used for a tangent: the central difference when both sides lie on the same
// surface, else the one-sided difference to the closer side, else none.
bool Tangent(const cv::Mat& depth, const std::vector<Eigen::Vector3d>& points, int u, int v, int du, int dv,
             Eigen::Vector3d& t) {
  const float z0 = depth.at<float>(v, u);
  auto sample = [&](int s) -> const Eigen::Vector3d* {
    const int uu = u + s * du, vv = v + s * dv;
    if (uu < 0 || vv < 0 || uu >= depth.cols || vv >= depth.rows) return nullptr;
    const float z = depth.at<float>(vv, uu);
    // A jump of more than 3 % of the depth between neighbours is an edge, not one surface.
    if (!std::isfinite(z) || std::abs(z - z0) > 0.03f * z0) return nullptr;
    return &points[static_cast<size_t>(vv) * depth.cols + uu];
  };
  const Eigen::Vector3d *plus = sample(1), *minus = sample(-1);
  const Eigen::Vector3d& centre = points[static_cast<size_t>(v) * depth.cols + u];
  if (plus && minus)
    t = *plus - *minus;
  else if (plus)
    t = *plus - centre;
  else if (minus)
    t = centre - *minus;
  else
    return false;
  return true;
}

}  // namespace

double AxialSigma(const KinectNoiseParams& p, double z, double theta) {
  double sigma = p.axial_a_m + p.axial_b_per_m * (z - p.axial_c_m) * (z - p.axial_c_m);
  if (theta > p.steep_angle_rad) {
    const double rest = std::max(M_PI / 2 - theta, 1e-3);
    sigma += p.steep_gain / std::sqrt(z) * theta * theta / (rest * rest);
  }
  return sigma * p.noise_scale;
}

double QuantizationStep(const KinectNoiseParams& p, double z) {
  return z * z / (p.ir_focal_px * p.baseline_m * p.subpixel);
}

cv::Mat IncidenceAngles(const cv::Mat& depth, const CameraIntrinsics& k) {
  cv::Mat theta(depth.size(), CV_32FC1, cv::Scalar(kNaN));
  const std::vector<Eigen::Vector3d> points = BackProjectAll(depth, k);
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth.at<float>(v, u);
      if (!std::isfinite(z)) continue;
      Eigen::Vector3d tu, tv;
      if (!Tangent(depth, points, u, v, 1, 0, tu) || !Tangent(depth, points, u, v, 0, 1, tv)) continue;
      const Eigen::Vector3d n = tu.cross(tv);
      const double norm = n.norm();
      if (norm <= 0) continue;
      const Eigen::Vector3d ray = points[static_cast<size_t>(v) * depth.cols + u].normalized();
      // In single precision, as it is kept: half the time of acos in double.
      const float c = static_cast<float>(std::min(1.0, std::abs(n.dot(ray)) / norm));
      theta.at<float>(v, u) = std::acos(c);
    }
  }
  return theta;
}

cv::Mat ProjectorShadowMask(const cv::Mat& depth, const CameraIntrinsics& k, double baseline_m) {
  // The projector, baseline_m along +x, sees pixel u at u_p = u - fx b / z. Scanning a row from the
  // right, a pixel is hidden from the projector when something to its right maps further left.
  cv::Mat mask(depth.size(), CV_8UC1, cv::Scalar(0));
  const double fb = k.fx * baseline_m;
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    unsigned char* m = mask.ptr<unsigned char>(v);
    double min_up = std::numeric_limits<double>::infinity();
    for (int u = depth.cols - 1; u >= 0; --u) {
      if (!std::isfinite(z[u])) continue;
      const double up = u - fb / z[u];
      if (up > min_up + 0.5) m[u] = 255;  // Half a pixel of slack for sampling.
      min_up = std::min(min_up, up);
    }
  }
  return mask;
}

std::string ToString(const KinectNoiseParams& p) {
  return fmt::format(
      "range {:g}-{:g} m, axial {:g} {:g} {:g}, steep {:g} {:g}, lateral {:g} {:g}, quantize {:d} {:g} {:g} {:g}, "
      "grazing {:g}-{:g}, shadows {:d}, scale {:g}, window {} px {:g} m, draws {}",
      p.min_range_m, p.max_range_m, p.axial_a_m, p.axial_b_per_m, p.axial_c_m, p.steep_gain, p.steep_angle_rad,
      p.lateral_a_px, p.lateral_b_px, p.quantize, p.ir_focal_px, p.baseline_m, p.subpixel, p.grazing_start_rad,
      p.grazing_end_rad, p.shadows, p.noise_scale, p.correlation_window_px, p.window_surface_m, kKinectNoiseDraws);
}

namespace {

// The window's mean at (u, v) tested neighbour by neighbour (`inverse`: each pixel's 1 / depth), for
// pixels whose window spans a depth edge or a steep surface.
float MeanOverSurface(const cv::Mat& depth, const cv::Mat& inverse, int u, int v, int half, float tolerance) {
  const float z0 = depth.at<float>(v, u);
  double disparity = 0;
  int n = 0;
  for (int y = std::max(0, v - half); y <= std::min(depth.rows - 1, v + half); ++y) {
    const float* row = depth.ptr<float>(y);
    const double* row_inverse = inverse.ptr<double>(y);
    for (int x = std::max(0, u - half); x <= std::min(depth.cols - 1, u + half); ++x) {
      const bool same_surface = std::abs(row[x] - z0) < tolerance;  // False for NaN.
      disparity += same_surface ? row_inverse[x] : 0.0;
      n += same_surface ? 1 : 0;
    }
  }
  return static_cast<float>(n / disparity);
}

}  // namespace

cv::Mat CorrelationWindowDepth(const cv::Mat& depth, int window, double surface_m) {
  if (window <= 1) return depth;
  if (depth.type() != CV_32FC1) throw std::invalid_argument("correlation window: expected a CV_32FC1 depth image");
  if (window % 2 == 0 || !(surface_m > 0)) {
    throw std::invalid_argument(
        fmt::format("correlation window: expected an odd window and a surface tolerance > 0, got {} px and {} m",
                    window, surface_m));
  }
  // No library filter keeps the mean to one surface. But where a window's nearest and farthest depths
  // (erosion and dilation) lie within the tolerance of its centre, every neighbour passes the test, and
  // the mean is box filters' sums of disparity over valid pixels; only windows across a depth edge are
  // tested neighbour by neighbour.
  cv::Mat valid;
  cv::compare(depth, depth, valid, cv::CMP_EQ);  // NaN compares unequal.
  cv::Mat nearest = depth.clone(), farthest = depth.clone(), disparity, count;
  nearest.setTo(std::numeric_limits<float>::infinity(), ~valid);
  farthest.setTo(-std::numeric_limits<float>::infinity(), ~valid);
  const cv::Mat box = cv::Mat::ones(window, window, CV_8UC1);
  cv::erode(nearest, nearest, box);  // Outside the image counts as nothing there, as below.
  cv::dilate(farthest, farthest, box);
  cv::Mat inverse;
  cv::divide(1.0, depth, inverse, CV_64F);
  inverse.setTo(0, ~valid);
  const cv::Size size(window, window);
  cv::boxFilter(inverse, disparity, CV_64F, size, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  valid.convertTo(count, CV_64F, 1.0 / 255);
  cv::boxFilter(count, count, CV_64F, size, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);

  const int half = window / 2;
  const float tolerance = static_cast<float>(surface_m);
  cv::Mat out = depth.clone();
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    const float *lo = nearest.ptr<float>(v), *hi = farthest.ptr<float>(v);
    const double *sum = disparity.ptr<double>(v), *n = count.ptr<double>(v);
    float* row_out = out.ptr<float>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (!std::isfinite(z[u])) continue;
      const bool one_surface = hi[u] - z[u] < tolerance && z[u] - lo[u] < tolerance;
      row_out[u] =
          one_surface ? static_cast<float>(n[u] / sum[u]) : MeanOverSurface(depth, inverse, u, v, half, tolerance);
    }
  }
  return out;
}

cv::Mat ApplyKinectNoise(const cv::Mat& ideal, const CameraIntrinsics& k, const KinectNoiseParams& p,
                         std::mt19937_64& rng) {
  if (ideal.type() != CV_32FC1 || ideal.cols != k.width || ideal.rows != k.height) {
    throw std::invalid_argument("ApplyKinectNoise: expected a CV_32FC1 depth image of " + std::to_string(k.width) +
                                "x" + std::to_string(k.height));
  }
  const cv::Mat windowed = CorrelationWindowDepth(ideal, p.correlation_window_px, p.window_surface_m);
  const cv::Mat theta = IncidenceAngles(ideal, k);  // Dropouts follow the real surface.
  const cv::Mat shadow =
      p.shadows ? ProjectorShadowMask(ideal, k, p.baseline_m) : cv::Mat(windowed.size(), CV_8UC1, cv::Scalar(0));
  // Every pixel's draws at once (three normals, one uniform), by OpenCV's generator (Ziggurat normals, a
  // quarter of the time std::normal_distribution takes), seeded from the frame's stream. Each pixel has
  // its own draws, so its noise does not depend on what the rest of the image holds.
  cv::RNG frame_rng(rng());
  cv::Mat normals(windowed.rows, windowed.cols, CV_64FC3), uniforms(windowed.rows, windowed.cols, CV_64FC1);
  frame_rng.fill(normals, cv::RNG::NORMAL, 0.0, 1.0);
  frame_rng.fill(uniforms, cv::RNG::UNIFORM, 0.0, 1.0);
  const double disparity_scale = p.ir_focal_px * p.baseline_m;  // disparity (px) = scale / z

  cv::Mat out(windowed.size(), CV_32FC1, cv::Scalar(kNaN));
  for (int v = 0; v < windowed.rows; ++v) {
    const cv::Vec3d* normal = normals.ptr<cv::Vec3d>(v);
    const double* uniform = uniforms.ptr<double>(v);
    for (int u = 0; u < windowed.cols; ++u) {
      const double n_u = normal[u][0], n_v = normal[u][1], n_z = normal[u][2], drop = uniform[u];
      const float t0 = theta.at<float>(v, u);
      const double t_here = std::isfinite(t0) ? t0 : 0.0;
      const double sigma_l =
          p.noise_scale * (p.lateral_a_px + p.lateral_b_px * t_here / std::max(M_PI / 2 - t_here, 1e-3));
      const int su = std::clamp(static_cast<int>(std::lround(u + sigma_l * n_u)), 0, windowed.cols - 1);
      const int sv = std::clamp(static_cast<int>(std::lround(v + sigma_l * n_v)), 0, windowed.rows - 1);
      const float z = windowed.at<float>(sv, su);
      if (!std::isfinite(z) || shadow.at<unsigned char>(sv, su)) continue;
      if (z < p.min_range_m || z > p.max_range_m) continue;
      const float ts = theta.at<float>(sv, su);
      const double t = std::isfinite(ts) ? ts : 0.0;
      const double p_drop = (t - p.grazing_start_rad) / (p.grazing_end_rad - p.grazing_start_rad);
      if (drop < p_drop) continue;
      double noisy = z + AxialSigma(p, z, t) * n_z;
      if (p.quantize) {
        const double disparity = std::round(disparity_scale / noisy * p.subpixel) / p.subpixel;
        if (disparity <= 0) continue;
        noisy = disparity_scale / disparity;
      }
      if (noisy < p.min_range_m || noisy > p.max_range_m) continue;
      out.at<float>(v, u) = static_cast<float>(noisy);
    }
  }
  return out;
}

}  // namespace sortcell::sim
