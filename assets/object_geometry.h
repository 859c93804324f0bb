#pragma once
/// @file
/// An imported object's geometry in its body frame, before it is written out: what it looks like
/// (one visual mesh and its texture) and what it collides with (convex hulls and primitives).

#include <Eigen/Geometry>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "assets/mass_properties.h"
#include "assets/object_import.h"
#include "assets/triangle_mesh.h"
#include "assets/urdf_object.h"

namespace sortcell::assets {

/// A collision primitive (box, cylinder or sphere) of a URDF, in the body frame.
struct Primitive {
  UrdfShape shape;  ///< kind, size; X_LS is its pose in the body frame.
  MassProperties Mass() const;
  /// Points whose hull bounds it closely (box corners, cylinder rims, a sphere's equator and poles).
  std::vector<Eigen::Vector3d> ExtentPoints() const;
};

struct ObjectGeometry {
  TriangleMesh visual;                ///< Empty when the object has no visual geometry.
  std::filesystem::path texture;      ///< The visual's texture image, if any (absolute).
  std::vector<TriangleMesh> hulls;    ///< Convex collision pieces.
  std::vector<Primitive> primitives;  ///< Collision primitives.
  std::vector<std::string> warnings;
  std::optional<double> urdf_mass;  ///< The URDF's <inertial> mass, if it gives one.

  /// Every collision hull vertex and primitive extent point.
  std::vector<Eigen::Vector3d> CollisionPoints() const;
  MassProperties Mass() const;
  /// Moves everything so that the body origin is the centre of the collision geometry's base.
  void Recentre();
};

/// The geometry of `source` (URDF or mesh), scaled, in the URDF's link frame.
/// @throws std::invalid_argument as ImportObject.
ObjectGeometry ReadObjectGeometry(const ObjectSource& source, const ImportLimits& limits);

}  // namespace sortcell::assets
