#pragma once
// A tabletop seen by a Kinect-like camera, ray-cast without a simulator: the table top (z = 0) and
// upright coloured cylinders, as an organized cloud in the camera's optical frame. For the policy's
// unit tests, which must run without MuJoCo.
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <vector>

#include "perception/cloud.h"

namespace sortcell_test {

struct Cylinder {
  Eigen::Vector2d xy;
  double radius = 0.03, height = 0.2;
  uint8_t r = 40, g = 160, b = 60;
};

// The Kinect of the cell: at (1.25, 0, 0.75) looking at (0.5, 0, 0), optical frame (x right, y down).
inline Eigen::Isometry3d KinectPose() {
  const Eigen::Vector3d p(1.25, 0, 0.75), target(0.5, 0, 0);
  const Eigen::Vector3d z = (target - p).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() << x, z.cross(x), z;
  X_WC.translation() = p;
  return X_WC;
}

// Distance along the ray o + t d to the cylinder (side or top), or infinity.
inline double HitCylinder(const Cylinder& c, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d oc = o.head<2>() - c.xy;
  const double a = d.head<2>().squaredNorm(), b = 2 * oc.dot(d.head<2>()), k = oc.squaredNorm() - c.radius * c.radius;
  const double disc = b * b - 4 * a * k;
  if (a > 0 && disc >= 0) {
    const double t = (-b - std::sqrt(disc)) / (2 * a);
    const double z = o.z() + t * d.z();
    if (t > 0 && z >= 0 && z <= c.height) best = t;
  }
  if (d.z() < 0) {
    const double t = (c.height - o.z()) / d.z();
    if (t > 0 && (o.head<2>() + t * d.head<2>() - c.xy).norm() <= c.radius) best = std::min(best, t);
  }
  return best;
}

inline sortcell::perception::Cloud::Ptr RenderTable(const std::vector<Cylinder>& objects, const Eigen::Isometry3d& X_WC,
                                                    int width = 640, int height = 480, double f = 525) {
  auto cloud = std::make_shared<sortcell::perception::Cloud>(width, height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const Eigen::Vector3d d_C((u - width / 2.0 + 0.5) / f, (v - height / 2.0 + 0.5) / f, 1.0);
      const Eigen::Vector3d o = X_WC.translation(), d = X_WC.linear() * d_C;
      double t = std::numeric_limits<double>::infinity();
      uint8_t r = 0, g = 0, b = 0;
      if (d.z() < 0) {
        const double t_table = -o.z() / d.z();
        const Eigen::Vector3d p = o + t_table * d;
        if (p.x() > -0.3 && p.x() < 0.9 && std::abs(p.y()) < 0.7) {
          t = t_table;
          r = 200, g = 180, b = 150;
        }
      }
      for (const auto& c : objects) {
        const double t_object = HitCylinder(c, o, d);
        if (t_object < t) {
          t = t_object;
          r = c.r, g = c.g, b = c.b;
        }
      }
      auto& p = cloud->at(u, v);
      if (std::isfinite(t)) {
        const Eigen::Vector3d p_C = t * d_C;  // d_C.z() = 1: t is the planar depth.
        p.x = static_cast<float>(p_C.x()), p.y = static_cast<float>(p_C.y()), p.z = static_cast<float>(p_C.z());
        p.r = r, p.g = g, p.b = b;
      } else {
        p.x = p.y = p.z = nan;
      }
    }
  }
  return cloud;
}

}  // namespace sortcell_test
