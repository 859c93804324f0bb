#include "perception/marker_sighting.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace sortcell::perception {
namespace {

cv::Mat GreyImage(const Cloud& cloud) {
  cv::Mat grey(static_cast<int>(cloud.height), static_cast<int>(cloud.width), CV_8UC1);
  for (int v = 0; v < grey.rows; ++v) {
    for (int u = 0; u < grey.cols; ++u) {
      const PointT& p = cloud.at(u, v);
      grey.at<unsigned char>(v, u) = static_cast<unsigned char>((299 * p.r + 587 * p.g + 114 * p.b) / 1000);
    }
  }
  return grey;
}

std::optional<std::array<Eigen::Vector2d, 4>> DetectCorners(const cv::Mat& grey, int id) {
  std::vector<int> ids;
  std::vector<std::vector<cv::Point2f>> corners;
  cv::Ptr<cv::aruco::DetectorParameters> detector = cv::aruco::DetectorParameters::create();
  detector->cornerRefinementMethod = cv::aruco::CORNER_REFINE_CONTOUR;
  cv::aruco::detectMarkers(grey, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), corners, ids, detector);
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] != id) continue;
    std::array<Eigen::Vector2d, 4> out;
    for (int c = 0; c < 4; ++c) out[c] = {corners[k][c].x, corners[k][c].y};
    return out;
  }
  return std::nullopt;
}

// Where the image diagonals of the quadrilateral cross: the projection of the square's centre.
Eigen::Vector2d DiagonalsCrossing(const std::array<Eigen::Vector2d, 4>& c) {
  const Eigen::Vector3d a = Eigen::Vector3d(c[0].x(), c[0].y(), 1).cross(Eigen::Vector3d(c[2].x(), c[2].y(), 1));
  const Eigen::Vector3d b = Eigen::Vector3d(c[1].x(), c[1].y(), 1).cross(Eigen::Vector3d(c[3].x(), c[3].y(), 1));
  const Eigen::Vector3d x = a.cross(b);
  return x.head<2>() / x.z();  // Diagonals of a detected (convex) quadrilateral always cross: z != 0.
}

struct Plane {
  Eigen::Vector3d point, normal;
  int points = 0;
  double rms = 0;
};

// Least-squares plane of the points, refitted without those beyond 2.5 sigma (pixels of what hides
// part of the plate or shows past its edge) until none are left out.
std::optional<Plane> FitPlane(std::vector<Eigen::Vector3d> points, int min_points) {
  constexpr int kPasses = 4;
  for (int pass = 0; pass < kPasses; ++pass) {
    if (static_cast<int>(points.size()) < min_points) return std::nullopt;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : points) mean += p;
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
    Plane plane{mean, eig.eigenvectors().col(0), static_cast<int>(points.size()),
                std::sqrt(eig.eigenvalues()(0) / static_cast<double>(points.size()))};
    if (plane.normal.dot(mean) > 0) plane.normal = -plane.normal;  // Towards the camera.
    std::vector<Eigen::Vector3d> kept;
    for (const auto& p : points) {
      // The floor: a noiseless plane's rms is ~0, and rounding must not reject its points.
      if (std::abs((p - mean).dot(plane.normal)) <= std::max(2.5 * plane.rms, 1e-4)) kept.push_back(p);
    }
    if (kept.size() == points.size() || pass == kPasses - 1) return plane;
    points = std::move(kept);
  }
  return std::nullopt;
}

std::vector<Eigen::Vector3d> PointsInside(const Cloud& cloud, const std::array<Eigen::Vector2d, 4>& corners,
                                          double scale) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& c : corners) centre += 0.25 * c;
  std::vector<cv::Point> quad;
  for (const auto& c : corners) {
    const Eigen::Vector2d g = centre + scale * (c - centre);
    quad.emplace_back(static_cast<int>(std::lround(g.x())), static_cast<int>(std::lround(g.y())));
  }
  cv::Mat mask = cv::Mat::zeros(static_cast<int>(cloud.height), static_cast<int>(cloud.width), CV_8UC1);
  cv::fillConvexPoly(mask, quad, cv::Scalar(255));
  std::vector<Eigen::Vector3d> points;
  for (int v = 0; v < mask.rows; ++v) {
    for (int u = 0; u < mask.cols; ++u) {
      const PointT& p = cloud.at(u, v);
      if (mask.at<unsigned char>(v, u) && std::isfinite(p.z)) points.emplace_back(p.x, p.y, p.z);
    }
  }
  return points;
}

}  // namespace

std::optional<MarkerSighting> FindMarker(const Cloud& cloud, const Pinhole& pinhole, int id,
                                         const MarkerSightingParams& params) {
  if (!cloud.isOrganized()) throw std::invalid_argument("FindMarker: the cloud is not organized");
  if (id < 0 || id >= 50)
    throw std::invalid_argument("FindMarker: marker id " + std::to_string(id) + " is not in 4x4_50");
  const auto corners = DetectCorners(GreyImage(cloud), id);
  if (!corners) return std::nullopt;
  const auto plane = FitPlane(PointsInside(cloud, *corners, params.plane_region_scale), params.min_plane_points);
  if (!plane) return std::nullopt;
  const Eigen::Vector3d ray = pinhole.Ray(DiagonalsCrossing(*corners));
  const double along = ray.dot(plane->normal);
  if (std::abs(along) < 1e-6) return std::nullopt;  // Seen edge-on.
  MarkerSighting sighting;
  sighting.p_C_centre = ray * (plane->point.dot(plane->normal) / along);
  sighting.n_C = plane->normal;
  sighting.corners_px = *corners;
  sighting.plane_points = plane->points;
  sighting.plane_rms_m = plane->rms;
  return sighting;
}

}  // namespace sortcell::perception
