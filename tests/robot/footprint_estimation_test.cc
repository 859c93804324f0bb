// Grasp footprints from synthetic "visible" point sets: what a camera at 45 degrees sees of a
// cylinder (front half of the side, a small cap) and of a box (top face and two sides).
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.h"
#include "robot/footprint_estimation.h"

namespace sortcell::robot {
namespace {

const Eigen::Vector3d kCamera(1.25, 0, 0.75);

// The camera-facing half of a cylinder's side (radius r, height h) at centre c, plus a cap of radius
// r_cap on top.
std::vector<Eigen::Vector3d> VisibleCylinder(const Eigen::Vector2d& c, double r, double h, double r_cap) {
  std::vector<Eigen::Vector3d> p;
  const Eigen::Vector2d to_camera = (kCamera.head<2>() - c).normalized();
  for (int i = 0; i < 180; ++i) {
    const double a = 2 * M_PI * i / 180;
    const Eigen::Vector2d n(std::cos(a), std::sin(a));
    if (n.dot(to_camera) <= 0) continue;
    for (double z = 0.01; z < h; z += 0.01) p.emplace_back(c.x() + r * n.x(), c.y() + r * n.y(), z);
  }
  for (double x = -r_cap; x <= r_cap; x += 0.003) {
    for (double y = -r_cap; y <= r_cap; y += 0.003) {
      if (x * x + y * y <= r_cap * r_cap) p.emplace_back(c.x() + x, c.y() + y, h + 0.02);
    }
  }
  return p;
}

// Top face and the two camera-facing sides of a box (half sizes a along x_B, b along y_B, height h)
// turned by `yaw`.
std::vector<Eigen::Vector3d> VisibleBox(const Eigen::Vector2d& c, double a, double b, double h, double yaw) {
  std::vector<Eigen::Vector3d> p;
  const Eigen::Rotation2Dd R(yaw);
  for (double x = -a; x <= a + 1e-9; x += 0.004) {
    for (double y = -b; y <= b + 1e-9; y += 0.004) {
      const Eigen::Vector2d q = c + R * Eigen::Vector2d(x, y);
      p.emplace_back(q.x(), q.y(), h);
    }
  }
  return p;
}

// The camera-facing part of a cylinder (radius r, length l) lying on the table along `yaw`, its axis
// r above the table: the surface points whose normal faces the camera.
std::vector<Eigen::Vector3d> VisibleLyingCylinder(const Eigen::Vector2d& c, double r, double l, double yaw) {
  std::vector<Eigen::Vector3d> p;
  const Eigen::Vector3d axis(std::cos(yaw), std::sin(yaw), 0), side(-std::sin(yaw), std::cos(yaw), 0);
  const Eigen::Vector3d centre(c.x(), c.y(), r);
  for (int i = 0; i < 180; ++i) {
    const double a = 2 * M_PI * i / 180;
    const Eigen::Vector3d n = std::cos(a) * side + std::sin(a) * Eigen::Vector3d::UnitZ();
    for (double t = -0.5 * l; t <= 0.5 * l; t += 0.005) {
      const Eigen::Vector3d q = centre + t * axis + r * n;
      if (q.z() > 0.002 && n.dot(kCamera - q) > 0) p.push_back(q);
    }
  }
  return p;
}

TEST(FootprintEstimation, ALyingCylinderIsPinchedAcrossItsAxisAtItsMiddle) {
  for (const double yaw : {0.0, 0.6, 1.57, 2.5}) {
    const Eigen::Vector2d centre(0.5, -0.1);
    const FootprintEstimate e = EstimateFootprint(VisibleLyingCylinder(centre, 0.033, 0.2, yaw), kCamera, 0.0);
    EXPECT_TRUE(e.lying) << yaw;
    EXPECT_FALSE(e.across_view) << yaw;
    EXPECT_FALSE(e.turned.has_value());
    const Eigen::Vector2d pinch(std::cos(e.footprint.pinch_yaw), std::sin(e.footprint.pinch_yaw));
    EXPECT_LT(std::abs(pinch.dot(Eigen::Vector2d(std::cos(yaw), std::sin(yaw)))), 0.05) << yaw;
    EXPECT_NEAR(e.footprint.width, 0.066, 0.004) << yaw;
    EXPECT_LT((e.footprint.centre_xy - centre).norm(), 0.006) << yaw;
    EXPECT_NEAR(e.footprint.top_z, 0.066, 0.002) << yaw;
  }
}

TEST(FootprintEstimation, CylinderIsPinchedAcrossTheLineOfSightAtItsTrueCentre) {
  const Eigen::Vector2d centre(0.5, 0.1);
  const FootprintEstimate e = EstimateFootprint(VisibleCylinder(centre, 0.033, 0.16, 0.015), kCamera, 0.0);
  EXPECT_TRUE(e.across_view);
  EXPECT_FALSE(e.prism);
  EXPECT_LT((e.footprint.centre_xy - centre).norm(), 0.003);
  EXPECT_NEAR(e.footprint.width, 0.066, 0.003);
  // Across the line of sight from the camera to the object.
  const Eigen::Vector2d view = (centre - kCamera.head<2>()).normalized();
  const Eigen::Vector2d pinch(std::cos(e.footprint.pinch_yaw), std::sin(e.footprint.pinch_yaw));
  EXPECT_LT(std::abs(pinch.dot(view)), 0.01);
  EXPECT_NEAR(e.footprint.top_z, 0.18, 1e-6);
  EXPECT_EQ(e.footprint.base_z, 0.0);
}

TEST(FootprintEstimation, CentroidWouldBeBiasedTowardsTheCamera) {
  // Why the estimate is not the centroid (the paper's grasp point): it lies on the visible half.
  const Eigen::Vector2d centre(0.5, 0.0);
  const auto points = VisibleCylinder(centre, 0.033, 0.16, 0.015);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p.head<2>();
  mean /= static_cast<double>(points.size());
  EXPECT_GT((mean - centre).norm(), 0.015);
  EXPECT_LT((EstimateFootprint(points, kCamera, 0.0).footprint.centre_xy - centre).norm(), 0.003);
}

TEST(FootprintEstimation, BoxAcrossTheLineOfSightIsPinchedAcrossItsNarrowSide) {
  // 60 x 90 mm box with its long side across the line of sight (the camera looks along -x).
  const Eigen::Vector2d centre(0.45, 0.05);
  const FootprintEstimate e = EstimateFootprint(VisibleBox(centre, 0.030, 0.045, 0.12, 0.0), kCamera, 0.0);
  EXPECT_TRUE(e.prism);
  EXPECT_FALSE(e.across_view);
  EXPECT_NEAR(e.footprint.width, 0.060, 0.004);
  EXPECT_LT(std::abs(std::sin(e.footprint.pinch_yaw)), 0.1);  // Along x: the 60 mm side.
  EXPECT_LT((e.footprint.centre_xy - centre).norm(), 0.004);
}

TEST(FootprintEstimation, TurnedBoxIsPinchedAcrossItsNarrowSide) {
  const Eigen::Vector2d centre(0.5, -0.1);
  const double yaw = 0.7;
  const FootprintEstimate e = EstimateFootprint(VisibleBox(centre, 0.030, 0.045, 0.12, yaw), kCamera, 0.0);
  EXPECT_NEAR(e.footprint.width, 0.060, 0.004);
  // The narrow side (x_B) direction, modulo pi.
  EXPECT_NEAR(std::abs(std::cos(e.footprint.pinch_yaw - yaw)), 1.0, 0.01);
  EXPECT_LT((e.footprint.centre_xy - centre).norm(), 0.004);
  // Its other pair of sides (0.09 m) fits the stroke too: the turned grasp, a quarter turn round.
  ASSERT_TRUE(e.turned.has_value());
  EXPECT_NEAR(e.turned->width, 0.090, 0.004);
  EXPECT_NEAR(std::abs(std::sin(e.turned->pinch_yaw - yaw)), 1.0, 0.01);
  EXPECT_FALSE(e.lying);
}

TEST(FootprintEstimation, RejectsTooFewPointsAndACameraAbove) {
  EXPECT_NE(sortcell_test::ErrorOf([] {
              EstimateFootprint({Eigen::Vector3d(0.5, 0, 0.1)}, kCamera, 0.0);
            }).find("at least 10 object points"),
            std::string::npos);
  const auto points = VisibleCylinder(Eigen::Vector2d(0.5, 0), 0.03, 0.1, 0.01);
  EXPECT_NE(sortcell_test::ErrorOf([&] {
              EstimateFootprint(points, Eigen::Vector3d(0.5, 0, 1.0), 0.0);
            }).find("right above the object"),
            std::string::npos);
}

// A bottle's visible side: a 3.3 cm body to 0.16 m, a shoulder narrowing to the 1.35 cm neck at 0.19 m,
// neck and cap to 0.224 m. It is full width up to its shoulder (the band from 0.17 m reaches 0.85 of
// its radius, the next does not); a straight can up to its top band; points of nothing: -infinity.
TEST(FootprintEstimation, AFullWidthTopIsBelowABottlesShoulder) {
  const Eigen::Vector2d c(0.5, 0.1);
  const Eigen::Vector2d to_camera = (kCamera.head<2>() - c).normalized();
  std::vector<Eigen::Vector3d> bottle;
  for (double z = 0.0005; z < 0.224; z += 0.002) {
    const double shoulder = (z - 0.16) / 0.035;
    const double r = z < 0.16   ? 0.033
                     : z < 0.19 ? std::fmax(0.0135, 0.033 * std::sqrt(std::fmax(0.0, 1 - shoulder * shoulder)))
                                : 0.0135;
    for (int i = 0; i < 90; ++i) {
      const Eigen::Vector2d n(std::cos(2 * M_PI * i / 90), std::sin(2 * M_PI * i / 90));
      if (n.dot(to_camera) > 0) bottle.emplace_back(c.x() + r * n.x(), c.y() + r * n.y(), z);
    }
  }
  ObjectFootprint f;
  f.centre_xy = c;
  f.top_z = 0.224;
  f.width = 0.066;
  EXPECT_NEAR(FullWidthTop(bottle, f), 0.17, 1e-9);
  const auto can = VisibleCylinder(c, 0.033, 0.10, 0.03);
  f.top_z = 0.12;
  EXPECT_NEAR(FullWidthTop(can, f), 0.09, 1e-9);
  EXPECT_EQ(FullWidthTop({}, f), -INFINITY);
}

}  // namespace
}  // namespace sortcell::robot
