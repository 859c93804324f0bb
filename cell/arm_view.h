#pragma once
/// @file
/// Whether the arm hides any of the workspace from the camera, decided from the robot's own
/// kinematics and the camera's calibrated pose: the arm's links (the URDF's collision envelope), the
/// gripper and what it may hold are capsules along the D-H chain, with a margin, and a capsule
/// hides the workspace when the shadow it casts from the camera (the cone of rays it blocks) reaches
/// a point of the workspace box's surface (sampled closer than the thinnest capsule).

#include <array>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "cell/scene_observation.h"
#include "robot/ur5_kinematics.h"
#include "sortcell/ur5_urdf.h"

namespace sortcell::cell {

/// An object between the fingers, as the robot knows it: a capsule from the TCP down.
struct HeldObject {
  double below_tcp = 0;  ///< How far it reaches below the TCP (its grasp height; negative: above it) (m).
  double radius = 0;     ///< Its horizontal reach from the TCP's axis (m).
};

/// A capsule (world frame, m): the segment a-b, widened by radius.
struct Capsule {
  Eigen::Vector3d a, b;
  double radius = 0;
};

/// The capsules of the arm's links, the gripper and what it holds, in a list of fixed capacity: the
/// checks that run every control period of a carry allocate nothing.
class CapsuleList {
 public:
  static constexpr size_t kCapacity = std::size(robot::ur5_urdf::kCollisionCapsules) + 2;  // + gripper, held.
  CapsuleList() = default;
  CapsuleList(std::initializer_list<Capsule> capsules) {
    for (const Capsule& c : capsules) push_back(c);
  }
  /// @throws std::length_error past kCapacity.
  void push_back(const Capsule& capsule) {
    if (size_ == kCapacity) throw std::length_error("CapsuleList: more than kCapacity capsules");
    items_[size_++] = capsule;
  }
  size_t size() const { return size_; }
  Capsule* begin() { return items_.data(); }
  Capsule* end() { return items_.data() + size_; }
  const Capsule* begin() const { return items_.data(); }
  const Capsule* end() const { return items_.data() + size_; }

 private:
  std::array<Capsule, kCapacity> items_{};
  size_t size_ = 0;
};

/// The capsules that stand for the arm, the gripper and `held` at joints q.
CapsuleList ArmCapsules(const robot::Joints& q, const std::optional<HeldObject>& held);

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
