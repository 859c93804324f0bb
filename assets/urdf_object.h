#pragma once
/// @file
/// A user's object described by a one-link URDF (as simulators publish scanned objects, e.g. the YCB
/// set): its visual mesh, its collision shapes (meshes or primitives), their origins and the mass.
/// Read with urdfdom; inertia and anything beyond one link are not taken from it.

#include <Eigen/Geometry>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sortcell::assets {

/// One <visual> or <collision> geometry, in the link frame.
struct UrdfShape {
  enum class Kind { kMesh, kBox, kCylinder, kSphere };
  Kind kind = Kind::kMesh;
  std::filesystem::path mesh;                       ///< Absolute (kMesh).
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  ///< Of the mesh.
  /// Box: full sizes; cylinder: (radius, length, 0) along z; sphere: (radius, 0, 0) (m).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  ///< Shape frame in the link frame.
};

struct UrdfObject {
  std::string name;  ///< <robot name>.
  std::vector<UrdfShape> visuals;
  std::vector<UrdfShape> collisions;
  std::optional<double> mass;  ///< kg, if <inertial> gives one.
};

/// @throws std::invalid_argument "URDF '<file>': <what>" for a missing or malformed file, not exactly
///         one link, a link with no collision geometry, a geometry kind other than mesh, box,
///         cylinder and sphere, non-positive or non-finite sizes, scales or mass, or a mesh file that
///         does not exist (paths relative to the URDF's folder; package:// is refused with the reason).
UrdfObject ReadUrdfObject(const std::filesystem::path& file);

/// The same from text; mesh paths relative to `folder`, `name` names the source in errors.
UrdfObject ParseUrdfObject(const std::string& text, const std::filesystem::path& folder, const std::string& name);

}  // namespace sortcell::assets
