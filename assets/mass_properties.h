#pragma once
/// @file
/// Volume, centre of mass and inertia of solids bounded by closed triangle meshes, and the convex hull
/// of a point set (what MuJoCo collides with when given a mesh).

#include <Eigen/Core>

#include <vector>

#include "assets/triangle_mesh.h"

namespace sortcell::assets {

/// Of a uniform solid of density 1: its volume (m^3), centroid, and inertia about the centroid (per
/// unit density, kg m^2 / (kg/m^3)).
struct MassProperties {
  double volume = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// Of the solid a closed, outward-oriented triangle mesh bounds (divergence theorem over the
/// tetrahedra from the origin to each triangle). An inward-oriented mesh gives the same with its
/// orientation fixed; an open mesh gives what its triangles enclose, which is meaningless.
MassProperties MassPropertiesOf(const TriangleMesh& closed);

/// Whether every edge of `mesh` is shared by exactly two triangles that run it in opposite
/// directions: a closed, consistently oriented surface, whose MassPropertiesOf means something.
bool IsClosedAndOriented(const TriangleMesh& mesh);

/// Of several solids together (their volumes add; they should not overlap).
MassProperties Combined(const std::vector<MassProperties>& parts);

/// The convex hull of `points` as an outward-oriented triangle mesh (qhull).
/// @throws std::invalid_argument if the points span no volume (fewer than 4, or all in a plane).
TriangleMesh ConvexHull(const std::vector<Eigen::Vector3d>& points);

/// The smallest width of the convex polygon around `points` (rotating calipers over its edges): the
/// narrowest opening a parallel gripper needs to close across it.
double MinimumWidth(const std::vector<Eigen::Vector2d>& points);

}  // namespace sortcell::assets
