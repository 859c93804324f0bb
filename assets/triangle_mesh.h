#pragma once
/// @file
/// A triangle mesh as the importer handles it: positions, optional per-vertex normals and texture
/// coordinates, triangles indexing them. Units are those of the file until the importer scales them.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace sortcell::assets {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  /// Per vertex, or empty.
  std::vector<Eigen::Vector3d> normals;
  /// Per vertex, or empty: (u, v) with (0, 0) at the texture image's top-left corner.
  std::vector<Eigen::Vector2d> uvs;

  /// The mesh moved by `X` (normals turned with it).
  TriangleMesh Transformed(const Eigen::Isometry3d& X) const;
  /// The mesh scaled by `s` about the origin (normals kept).
  TriangleMesh Scaled(const Eigen::Vector3d& s) const;
};

}  // namespace sortcell::assets
