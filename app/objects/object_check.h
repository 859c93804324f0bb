#pragma once
/// @file
/// `sortcell objects check`: every object of a set dropped on the cell's table, watched until it
/// settles: where and how it comes to rest (no jitter, no creep, no bounce), its size against the
/// gripper, a still of them all and a scene file mujoco-simulate opens.

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "files/object_set.h"

namespace sortcell::app {

/// What counts as resting, after ObjectCheckOptions::settle_s on the table. Judged on the pose, not
/// the velocity: soft contacts on a scanned mesh's hull chatter at a few 0.01 rad/s with no visible
/// motion (a tenth of a milliradian), which is not what a user means by jitter.
struct RestLimits {
  double creep = 0.002;     ///< Largest travel of the body origin over the last second (m).
  double turn_deg = 1.0;    ///< Largest rotation over the last second (deg).
  double jitter = 0.0005;   ///< Largest excursion of the origin within the last 0.5 s (m).
  double jitter_deg = 0.2;  ///< Largest excursion of the orientation within the last 0.5 s (deg).
  double bounce = 0.005;    ///< Largest rise above its resting height after the first impact (m).
};

struct ObjectCheckOptions {
  double drop_height = 0.02;  ///< Released this far above its resting height (m).
  double settle_s = 3.0;      ///< Watched this long (s).
  RestLimits limits;
};

struct ObjectCheckResult {
  std::string name, category;
  Eigen::Vector3d p_W_dropped = Eigen::Vector3d::Zero();  ///< Where its base centre was released.
  Eigen::Vector3d p_W_settled = Eigen::Vector3d::Zero();  ///< Its body origin at the end.
  double tilt_deg = 0;                                    ///< Of its z axis from vertical at the end.
  double yaw_deg = 0;                                     ///< Of its x axis about the vertical at the end.
  double end_speed = 0, end_spin = 0;  ///< Largest speeds in the last 0.5 s (m/s, rad/s), for the record.
  double creep = 0, turn_deg = 0;      ///< Travel and rotation over the last second.
  double jitter = 0, jitter_deg = 0;   ///< Excursions within the last 0.5 s.
  double bounce = 0;
  bool on_table = false;   ///< Its body origin ends above the table, within it.
  bool rests = false;      ///< On the table and within every RestLimits.
  std::string why_not;     ///< For one that does not rest: which limit it broke.
  double grip_width = 0;   ///< Narrowest width of its upright footprint (m).
  bool graspable = false;  ///< grip_width fits the gripper's stroke.
  /// Of its footprint laid on its side, for an object that can lie (sim::ObjectShape::lying).
  std::optional<double> grip_width_lying;
  std::optional<assets::ImportReport> import;
};

struct ObjectCheck {
  std::vector<ObjectCheckResult> objects;
  std::vector<std::filesystem::path> stills;  ///< One PNG per batch of objects on the table.
  std::filesystem::path scene;                ///< For mujoco-simulate: the cell with the set's objects.
};

/// Drops every object of `set` (in batches that fit the table, each object on its own spot) and writes
/// check.json, the stills (objects_<k>.png) and scene.xml into `out`.
/// @throws std::invalid_argument for an unusable output folder; std::runtime_error if MuJoCo diverges.
ObjectCheck CheckObjects(const files::ObjectSet& set, const std::filesystem::path& out,
                         const ObjectCheckOptions& options = {});

}  // namespace sortcell::app
