#pragma once
/// @file
/// Importing a user's object (a one-link URDF, or a bare OBJ/STL mesh) into an MJCF fragment the cell
/// includes like its own object models (models/objects/objects.inc.xml's conventions): one free body
/// named after the object, its origin at the centre of its base, resting on z = 0; a visual mesh with
/// its texture; one collision mesh per convex piece; inertia from the collision volume and the mass.
/// Generated files go to a cache folder keyed by a digest of the inputs, never beside the user's files.

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "robot/gripper_geometry.h"

namespace sortcell::assets {

/// Where an object comes from and what the user says of it (an object set's entry).
struct ObjectSource {
  std::string name;                ///< The body's name in the scene.
  std::filesystem::path urdf;      ///< A one-link URDF, or
  std::filesystem::path mesh;      ///< an OBJ or STL mesh (then `mass` or `density` is required).
  std::optional<double> mass;      ///< kg; overrides the URDF's.
  std::optional<double> density;   ///< kg/m^3, with the collision volume, when no mass is given.
  double scale = 1;                ///< Applied to every mesh (e.g. 0.001 for a file in millimetres).
  std::optional<double> friction;  ///< Sliding friction coefficient (default: the cell's objects').

  /// The file it comes from (the URDF or the mesh), for messages.
  const std::filesystem::path& file() const { return urdf.empty() ? mesh : urdf; }
};

/// What the import did, for the user (sortcell objects check) and the log.
struct ImportReport {
  std::string name;
  std::string source;                              ///< The URDF or mesh file.
  int collision_pieces = 0;                        ///< Convex collision geoms (mesh pieces and primitives).
  double volume = 0;                               ///< Of the collision geometry (m^3).
  double mass = 0;                                 ///< kg.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< Extent of the collision geometry, body axes (m).
  Eigen::Vector3d com = Eigen::Vector3d::Zero();   ///< Centre of mass in the body frame (m).
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();  ///< kg m^2, ascending.
  double grip_width = 0;                                        ///< Narrowest width across the upright footprint (m).
  bool graspable = true;                                        ///< grip_width fits the gripper's stroke.
  std::string texture;                                          ///< The texture file used, if any.
  std::vector<std::string> warnings;
};

struct ImportedObject {
  std::filesystem::path fragment;  ///< The MJCF fragment to include (absolute, in the cache).
  ImportReport report;
  bool from_cache = false;
};

/// What the importer checks an object against.
struct ImportLimits {
  double max_grip_width = robot::kMaxGap;  ///< The gripper's stroke (m).
  double min_size = 0.005;                 ///< Largest extent below this: wrong units (m).
  double max_size = 1.0;                   ///< Largest extent above this: wrong units (m).
  int max_pieces = 64;                     ///< More disconnected pieces are hulled as one, with a warning.
};

/// Imports `source` into `cache_root`/<name>-<digest>/ (object.inc.xml, visual.msh, texture.png,
/// report.json), or returns the cached import of the same inputs. Safe to call from concurrent
/// processes (written to a temporary folder, then renamed).
/// @throws std::invalid_argument naming the file for a missing or malformed URDF, mesh or texture, no
///         or a non-positive mass, non-finite vertices, or a size outside the limits (wrong units).
ImportedObject ImportObject(const ObjectSource& source, const std::filesystem::path& cache_root,
                            const ImportLimits& limits = {});

/// A digest of the inputs of `source` (its files' bytes, the mesh folders' materials and images, its
/// options): the cache key.
std::string SourceDigest(const ObjectSource& source);

/// 16 hex digits telling versions of `content` apart (std::hash: not cryptographic, stable for a build).
std::string ContentDigest(const std::string& content);

}  // namespace sortcell::assets
