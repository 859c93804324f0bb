#pragma once
/// @file
/// Puts objects where a scene generator wants them (datasets, randomised scenes): directly in the
/// state, at rest, standing on the table. Ground-truth tools, never used by the sorting loop.

#include <Eigen/Core>

#include <optional>
#include <random>
#include <vector>

#include "sim/model.h"
#include "sim/object_shape.h"

namespace sortcell::sim {

/// Fresh starts of a random arrangement before it gives up (early objects can block the rest).
inline constexpr int kPlacementArrangements = 50;

/// Sets free body `body` upright with its base centre at (x, y, 0) and yaw about z, velocity zero.
/// @throws std::invalid_argument naming the scene and body if it is not a free body.
void PlaceObject(const Model& model, Data& data, int body, double x, double y, double yaw);

/// Moves free body `body` out of the way: high above the cell, out of every camera's view, at a spot
/// of its own (`slot`) so parked objects never touch. For rendering only (they would fall if stepped).
void ParkObject(const Model& model, Data& data, int body, int slot);

/// Moves free body `body` out of the way for a simulation that is stepped: standing on the table's
/// plane (unbounded for collision in MuJoCo 2.2) 2.5 m or more behind and beside the robot, out of
/// every camera's view, at a spot of its own (`slot`) so stowed objects never touch.
void StowObject(const Model& model, Data& data, int body, int slot);

/// An object pose on the table: base centre (footprint origin) and yaw, upright or on its side.
struct TablePose {
  double x = 0, y = 0, yaw = 0;
  bool lying = false;  ///< Laid on its side (ObjectShape::lying) before the yaw.
};

/// Sets free body `body` resting on the table at `pose` as `shape` says (upright, or on its side
/// when pose.lying), velocity zero.
/// @throws std::invalid_argument naming the scene and body if it is not a free body, or if the pose
///         lies and the shape cannot.
void PlaceObject(const Model& model, Data& data, int body, const TablePose& pose, const ObjectShape& shape);

/// Where random scenes put objects, for episodes and training scenes alike (one distribution by
/// construction): the reachable middle of the workspace, with 3 cm of free table between footprints
/// so the open fingers fit between neighbours and objects segment apart.
struct PlacementArea {
  Eigen::Vector2d min{0.32, -0.22};  ///< World x, y (m).
  Eigen::Vector2d max{0.68, 0.22};
  double gap_m = 0.03;  ///< Free table between footprints (m).
};

/// Random non-overlapping poses for objects of footprint `radii` inside the rectangle [min, max]
/// (x, y): centres at least r_i + r_j + gap apart, yaw uniform. Rejection sampling, at most
/// `max_tries` draws per object and up to kPlacementArrangements fresh arrangements; nullopt when the
/// objects do not fit.
std::optional<std::vector<TablePose>> SampleTablePoses(const std::vector<double>& radii, const Eigen::Vector2d& min,
                                                       const Eigen::Vector2d& max, double gap, std::mt19937_64& rng,
                                                       int max_tries = 500);
/// The same inside `area`.
std::optional<std::vector<TablePose>> SampleTablePoses(const std::vector<double>& radii, const PlacementArea& area,
                                                       std::mt19937_64& rng, int max_tries = 500);

}  // namespace sortcell::sim
