#pragma once
/// @file
/// Ground truth read from the simulator, for scoring results and for the scripted `sortcell pick`
/// (which is allowed to know where an object is). Never used by a decision of the sorting loop.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sim/model.h"

namespace sortcell::sim {

/// An object's extent as a top-down grasp needs it, from its collision geoms in the current state.
struct ObjectExtent {
  Eigen::Vector2d centre_xy;  ///< Middle of the extent along pinch_yaw; across it, the centre of mass.
  double base_z = 0, top_z = 0;
  double pinch_yaw = 0;  ///< Horizontal direction of the smallest width, in [0, pi) (1 degree steps).
  double width = 0;      ///< Extent along pinch_yaw (m).
};

/// @throws std::invalid_argument naming the scene and body if `body` has no collision geom.
ObjectExtent ObjectExtentOf(const Model& model, const Data& data, int body);

/// The geoms of `body` that collide (contype or conaffinity set): what the object is to the physics.
std::vector<int> CollisionGeoms(const mjModel* m, int body);

/// Pose of a body in the world frame (after mj_kinematics / a step).
Eigen::Isometry3d BodyPose(const Data& data, int body);
/// Pose of a site in the world frame.
Eigen::Isometry3d SitePose(const Data& data, int site);

/// A bin: a body named "bin_<name>" with a box site of the same name at its floor centre, whose
/// half sizes are the bin's inside (scenes/cells/*.yaml, written by files/cell_file.h).
struct BinRef {
  std::string name;
  int body = -1;
  int site = -1;
  Eigen::Vector2d inner_half = Eigen::Vector2d::Zero();  ///< Half the inside along the bin's x and y (m).
};
/// "bin_<name>": the one place that spells a bin's body and site name.
std::string BinName(const std::string& category);
/// The scene's bins, in body order.
/// @throws std::invalid_argument naming the scene and bin if a bin body has no box floor site.
std::vector<BinRef> Bins(const Model& model);

/// True when the body's centre of mass lies inside the bin: within its inside seen from above and
/// less than 0.15 m above its floor, which an object standing upright in the bin satisfies (the
/// tallest, 0.224 m bottles, have it at 0.11 m) and one resting on the rim or held above the bin
/// does not.
bool InBin(const Data& data, int object_body, const BinRef& bin);

}  // namespace sortcell::sim
