// The marker found in an organized RGB-D cloud: the pinhole from the cloud's own points, the centre
// where it was drawn on a tilted plane, nothing where there is no marker, misuse named.
#include "perception/marker_sighting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/aruco.hpp>

#include "perception/cloud_pinhole.h"

namespace sortcell::perception {
namespace {

constexpr double kF = 525, kCx = 319.5, kCy = 239.5, kSide = 0.056;

// A plane through `centre` with normal `normal`, seen through the pinhole above; white, with marker
// `id` (kSide wide, 1-cell border) drawn centred on `centre` when id >= 0.
Cloud::Ptr PlaneWithMarker(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, int id) {
  cv::Mat marker;
  if (id >= 0) cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), id, 600, marker, 1);
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d s = n.cross(Eigen::Vector3d::UnitY()).normalized(), t = s.cross(n);  // Not mirrored.
  auto cloud = std::make_shared<Cloud>(640, 480);
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const Eigen::Vector3d ray((u - kCx) / kF, (v - kCy) / kF, 1.0);
      const Eigen::Vector3d p = ray * (centre.dot(n) / ray.dot(n));
      PointT& point = cloud->at(u, v);
      point.x = static_cast<float>(p.x()), point.y = static_cast<float>(p.y()), point.z = static_cast<float>(p.z());
      unsigned char grey = 255;
      const double a = (p - centre).dot(s) / kSide + 0.5, b = (p - centre).dot(t) / kSide + 0.5;
      if (id >= 0 && a >= 0 && a < 1 && b >= 0 && b < 1)
        grey = marker.at<unsigned char>(static_cast<int>(b * 600), static_cast<int>(a * 600));
      point.r = point.g = point.b = grey;
    }
  }
  return cloud;
}

TEST(FitPinhole, ReadsTheIntrinsicsFromTheCloudsPoints) {
  const auto cloud = PlaneWithMarker({0, 0, 1}, {0.2, 0, -1}, -1);
  const Pinhole pinhole = FitPinhole(*cloud);
  EXPECT_NEAR(pinhole.fx, kF, 1e-3);
  EXPECT_NEAR(pinhole.fy, kF, 1e-3);
  EXPECT_NEAR(pinhole.cx, kCx, 1e-3);
  EXPECT_NEAR(pinhole.cy, kCy, 1e-3);
}

TEST(FindMarker, FindsTheCentreOnATiltedPlane) {
  const Eigen::Vector3d centre(0.05, -0.03, 1.05);
  const auto cloud = PlaneWithMarker(centre, {0.4, -0.2, -1}, 7);
  const auto seen = FindMarker(*cloud, FitPinhole(*cloud), 7);
  ASSERT_TRUE(seen.has_value());
  EXPECT_LT((seen->p_C_centre - centre).norm(), 0.0005);
  EXPECT_GT(seen->n_C.dot(Eigen::Vector3d(0.4, -0.2, -1).normalized()), 0.9999) << "towards the camera";
  EXPECT_GT(seen->plane_points, 300);
  EXPECT_LT(seen->plane_rms_m, 1e-4);
}

TEST(FindMarker, FindsNothingWithoutTheMarker) {
  const auto plain = PlaneWithMarker({0, 0, 1}, {0, 0, -1}, -1);
  EXPECT_FALSE(FindMarker(*plain, FitPinhole(*plain), 7).has_value());
  const auto other = PlaneWithMarker({0, 0, 1}, {0, 0, -1}, 3);
  EXPECT_FALSE(FindMarker(*other, FitPinhole(*other), 7).has_value()) << "another marker";
}

TEST(FindMarker, NamesMisuse) {
  const auto cloud = PlaneWithMarker({0, 0, 1}, {0, 0, -1}, 7);
  const Pinhole pinhole = FitPinhole(*cloud);
  EXPECT_THROW(FindMarker(*cloud, pinhole, 50), std::invalid_argument);
  Cloud unorganized;
  unorganized.push_back(cloud->at(0, 0));
  EXPECT_THROW(FindMarker(unorganized, pinhole, 7), std::invalid_argument);
  EXPECT_THROW(FitPinhole(unorganized), std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::perception
