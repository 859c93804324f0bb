#pragma once
/// @file
/// The simulated arm and gripper as a robot controller sees them: joint encoders, torque commands,
/// the arm's bias torques (the dynamics model a real controller carries), finger servo targets, finger
/// encoders and pad contact forces. Nothing here reveals object poses or identities.
/// All calls are allocation-free (they run in the control loop).

#include <array>

#include <Eigen/Core>

#include "robot/gripper_control.h"
#include "sim/model.h"

namespace sortcell::sim {

using Vector6 = Eigen::Matrix<double, 6, 1>;

class ArmIo {
 public:
  /// Resolves the UR5's joints and motors (models/ur5) and the gripper's joints, servos and pads
  /// (models/gripper). @throws std::invalid_argument naming the scene and the missing element.
  explicit ArmIo(const Model& model);

  void ReadArm(const Data& data, Vector6& q, Vector6& qd) const;
  /// Motor torques (N m); the model clamps them to its ctrlrange as well.
  void SetArmTorques(Data& data, const Vector6& tau) const;
  /// Puts the arm at q at rest (for resets, before the first step).
  void SetArmPosition(Data& data, const Vector6& q) const;

  /// Both finger servos to this half-gap (m).
  void SetGripperTarget(Data& data, double half_gap) const;
  /// Each finger servo to its own half-gap target (m).
  void SetFingerTargets(Data& data, double left_half_gap, double right_half_gap) const;
  /// The gripper's sensors: finger gaps and speeds, pad forces, shear and twist.
  robot::GripperSensors ReadGripper(const Data& data) const;
  /// Puts both fingers at this half-gap at rest, with the servos holding it.
  void SetGripperPosition(Data& data, double half_gap) const;

 private:
  const mjModel* m_;
  std::array<int, 6> qpos_{}, dof_{}, motor_{};
  std::array<int, 2> finger_qpos_{}, finger_dof_{}, finger_servo_{};
  std::array<int, 4> pads_{};  ///< left upper, left lower, right upper, right lower
};

}  // namespace sortcell::sim
