#pragma once
/// @file
/// Whether the arm hides any of the workspace from the camera, decided from the robot's own
/// kinematics and the camera's calibrated pose: the arm's links (the URDF's collision envelope), the
/// gripper and what it may hold are capsules along the D-H chain, with a margin, and a capsule
/// hides the workspace when the shadow it casts from the camera (the cone of rays it blocks) reaches
/// a point of the workspace box's surface (sampled closer than the thinnest capsule).

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "cell/scene_observation.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// An object between the fingers, as the robot knows it: a capsule from the TCP down.
struct HeldObject {
  double below_tcp = 0;  ///< How far it reaches below the TCP (its grasp height) (m).
  double radius = 0;     ///< Its horizontal reach from the TCP's axis (m).
};

/// The capsules (world frame, m) that stand for the arm, the gripper and `held` at joints q.
struct Capsule {
  Eigen::Vector3d a, b;
  double radius = 0;
};
std::vector<Capsule> ArmCapsules(const robot::Joints& q, const std::optional<HeldObject>& held);

/// The calibrated camera's view of the workspace box [workspace_min_W, workspace_max_W].
class WorkspaceView {
 public:
  WorkspaceView(const CameraCalibration& camera, const Eigen::Vector3d& workspace_min_W,
                const Eigen::Vector3d& workspace_max_W);

  /// True if at joints q the arm (with `held` between the fingers, if any) hides part of the box from
  /// the camera, or lies in it.
  bool ArmInView(const robot::Joints& q, const std::optional<HeldObject>& held) const;

 private:
  Eigen::Vector3d p_WC_;  // The camera.
  // Points on the box's surface as seen from the camera: their offsets from it (world frame) and their
  // distances, computed once (ArmInView runs every control period of a carry).
  std::vector<Eigen::Vector3d> surface_from_camera_W_;
  std::vector<double> surface_range_;
};

}  // namespace sortcell::cell
