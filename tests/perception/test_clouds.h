#pragma once
// Synthetic clouds for perception tests (camera optical frame: z forward).
#include <cmath>
#include <limits>

#include "perception/cloud.h"

namespace sortcell_test {

using sortcell::perception::Cloud;
using sortcell::perception::PointT;

inline PointT Point(double x, double y, double z, uint8_t r, uint8_t g, uint8_t b) {
  PointT p;
  p.x = static_cast<float>(x);
  p.y = static_cast<float>(y);
  p.z = static_cast<float>(z);
  p.r = r;
  p.g = g;
  p.b = b;
  return p;
}

// The camera-facing half of an upright cylinder (axis along the camera's y) at distance z0, 2 mm spacing.
inline Cloud CylinderFront(double radius, double height, double z0, uint8_t r, uint8_t g, uint8_t b, double x0 = 0.0) {
  Cloud cloud;
  for (double y = -height / 2; y <= height / 2; y += 0.002) {
    for (double a = -M_PI / 2; a <= M_PI / 2; a += 0.002 / radius) {
      cloud.push_back(Point(x0 + radius * std::sin(a), y, z0 - radius * std::cos(a), r, g, b));
    }
  }
  return cloud;
}

// The camera-facing half of a sphere at distance z0.
inline Cloud SphereFront(double radius, double z0, uint8_t r, uint8_t g, uint8_t b) {
  Cloud cloud;
  for (double el = -M_PI / 2; el <= M_PI / 2; el += 0.002 / radius) {
    for (double a = -M_PI / 2; a <= M_PI / 2; a += 0.002 / radius) {
      cloud.push_back(Point(radius * std::cos(el) * std::sin(a), radius * std::sin(el),
                            z0 - radius * std::cos(el) * std::cos(a), r, g, b));
    }
  }
  return cloud;
}

inline void AddNan(Cloud& cloud, int n) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < n; ++i) {
    PointT p = Point(0, 0, 0, 1, 2, 3);
    p.x = p.y = p.z = nan;
    cloud.push_back(p);
  }
}

}  // namespace sortcell_test
