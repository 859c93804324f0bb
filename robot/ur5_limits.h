#pragma once
/// @file
/// The UR5's joint, speed and torque limits and URScript's default motion parameters.

#include "robot/ur5_kinematics.h"
#include "sortcell/ur5_urdf.h"

namespace sortcell::robot {

struct JointLimits {
  Joints lower;
  Joints upper;
};

/// Joints +-2 pi; the elbow restricted to +-pi (as UR cells usually configure it, and as the MJCF
/// model's elbow range is). From models/ur5/ur5.urdf, as the speed and torque limits below.
inline JointLimits Ur5JointLimits() {
  JointLimits limits;
  for (int i = 0; i < 6; ++i) {
    limits.lower[i] = ur5_urdf::kJointLower[i];
    limits.upper[i] = ur5_urdf::kJointUpper[i];
  }
  return limits;
}

/// Every joint's speed limit (rad/s, pi): the URDF gives all six the same, and the code relies on it.
inline constexpr double kUr5MaxJointSpeed = ur5_urdf::kJointVelocity[0];
constexpr bool EveryJointHasTheSameSpeedLimit() {
  for (double speed : ur5_urdf::kJointVelocity) {
    if (speed != kUr5MaxJointSpeed) return false;
  }
  return true;
}
static_assert(EveryJointHasTheSameSpeedLimit(),
              "models/ur5/ur5.urdf: every joint's <limit velocity> must be the same (kUr5MaxJointSpeed)");

/// Joint torque limits (N m): 150 for joints 1-3, 28 for joints 4-6.
inline Joints Ur5TorqueLimits() { return Joints(ur5_urdf::kJointEffort); }

/// Joint accelerations (rad/s^2) that the torque limits allow anywhere in the cell's workspace with the
/// gripper and a 0.5 kg payload, leaving a fifth of each limit to the controller's feedback: the
/// torque M(q) qdd + bias(q, qd) at these accelerations and pi rad/s stays within 80 % of
/// Ur5TorqueLimits() for every sampled pose (tests/sim/acceleration_limits_test.cc measures it on the
/// simulated arm). The shoulder pan carries no gravity load and is limited by inertia alone.
inline Joints Ur5AccelerationLimits() { return (Joints() << 12.0, 2.5, 6.0, 40.0, 40.0, 40.0).finished(); }

/// URScript movej defaults: 1.05 rad/s, 1.4 rad/s^2; movel: 0.25 m/s (1.2 m/s^2).
inline constexpr double kMovejSpeed = 1.05;
inline constexpr double kMovejAcceleration = 1.4;
inline constexpr double kMovelSpeed = 0.25;
inline constexpr double kMovelAcceleration = 1.2;

}  // namespace sortcell::robot
