#pragma once
/// @file
/// The plane fit of a neighbourhood from its first and second moments, shared by the descriptor's and
/// the crease test's normals (normal_estimation.cc) and the supervoxels' voxel normals
/// (supervoxel_normals.cc).

#include <pcl/features/normal_3d.h>

#include <Eigen/Core>
#include <limits>

#include "perception/cloud.h"

namespace sortcell::perception {

/// The sums of 1, x, y, z, xx, xy, xz, yy, yz, zz over a neighbourhood, in double about a common origin,
/// so that the covariance E[pp'] - E[p]E[p]' keeps its digits.
struct Moments {
  Eigen::Matrix<double, 10, 1> sums = Eigen::Matrix<double, 10, 1>::Zero();

  static Moments Of(const Eigen::Vector3d& p) {
    Moments m;
    m.sums << 1, p.x(), p.y(), p.z(), p.x() * p.x(), p.x() * p.y(), p.x() * p.z(), p.y() * p.y(), p.y() * p.z(),
        p.z() * p.z();
    return m;
  }
  void Add(const Moments& other) { sums += other.sums; }
  double n() const { return sums[0]; }
};

/// The plane fit of a neighbourhood (PCL's solvePlaneParameters), facing the camera at the origin from
/// `p_C`; NaN where fewer than 3 neighbours.
inline pcl::Normal NormalOf(const Moments& m, const Eigen::Vector3f& p_C) {
  pcl::Normal normal;
  if (m.n() < 3) {
    normal.normal_x = normal.normal_y = normal.normal_z = normal.curvature = std::numeric_limits<float>::quiet_NaN();
    return normal;
  }
  const Eigen::Matrix<double, 10, 1> e = m.sums / m.n();
  const Eigen::Vector3d mean = e.segment<3>(1);
  Eigen::Matrix3d covariance;
  covariance << e[4], e[5], e[6], e[5], e[7], e[8], e[6], e[8], e[9];
  covariance -= mean * mean.transpose();
  pcl::solvePlaneParameters(Eigen::Matrix3f(covariance.cast<float>()), normal.normal_x, normal.normal_y,
                            normal.normal_z, normal.curvature);
  pcl::flipNormalTowardsViewpoint(PointT(p_C.x(), p_C.y(), p_C.z()), 0.0f, 0.0f, 0.0f, normal.normal_x, normal.normal_y,
                                  normal.normal_z);
  return normal;
}

}  // namespace sortcell::perception
