#pragma once
/// @file
/// An object's shape as a scene generator needs it: how it rests on the table (upright, or laid on
/// its side), how high its origin then stands, and its footprint on the table as a convex polygon.
/// From the body's collision geoms in the model (not the state): ground-truth tools for placing
/// objects, never used by the sorting loop.

#include <Eigen/Geometry>

#include <optional>
#include <vector>

#include "sim/model.h"

namespace sortcell::sim {

/// One way an object rests on the table.
struct RestingShape {
  /// Rotation of the body from its modelled (upright) orientation, applied before the yaw about z.
  Eigen::Quaterniond q_tilt = Eigen::Quaterniond::Identity();
  double origin_z = 0;  ///< Height of the body origin above the table (its lowest point touches it).
  double height = 0;    ///< Of its highest point above the table (m).
  /// Its footprint seen from above at yaw 0, body origin at (0, 0): convex, counter-clockwise (m).
  std::vector<Eigen::Vector2d> outline;
  double radius = 0;  ///< Largest distance of the outline from the origin (m).
  /// The middle of the outline's bounding box (at yaw 0), and the outline's largest distance from it:
  /// the disc it fits in (m). A lying bottle's origin is at its base, a bottle's length from its cap.
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();
  double middle_radius = 0;
};

struct ObjectShape {
  RestingShape upright;
  /// Radius of the upright footprint about the body origin, from each geom's own extent (cylinders
  /// and spheres their radius, boxes their corners, meshes their bounding sphere): the disc that
  /// sparse placement keeps apart.
  double disc_radius = 0;
  /// Laid on its side (the side that rests lowest, the stablest), for objects clearly taller than they
  /// are narrow (bottles, boxes, cans); none for balls, fruit and squat objects such as the cup.
  std::optional<RestingShape> lying;

  /// On its side when `lying` and it can lie, else upright.
  const RestingShape& Resting(bool lying_down) const { return lying_down && lying ? *lying : upright; }
};

/// The shape of free body `body` from its collision geoms.
/// @throws std::invalid_argument naming the scene and body if it has no collision geom.
ObjectShape ObjectShapeOf(const Model& model, int body);

/// `outline` turned by `yaw` about the origin and moved to `centre`.
std::vector<Eigen::Vector2d> PlacedOutline(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& centre,
                                           double yaw);

/// How far apart two convex polygons are along the axis that separates them best (m): > 0 apart,
/// <= 0 overlapping (the depth along the least-overlapping axis). A lower bound on their distance.
double Separation(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

}  // namespace sortcell::sim
