#pragma once
/// @file
/// The UR5's joint, speed and torque limits and URScript's default motion parameters.

#include "robot/ur5_kinematics.h"

namespace sortcell::robot {

struct JointLimits {
  Joints lower;
  Joints upper;
};

/// Joints +-2 pi; the elbow restricted to +-pi (as UR cells usually configure it, and as the MJCF
/// model's elbow range is).
inline JointLimits Ur5JointLimits() {
  JointLimits limits;
  limits.upper.setConstant(2.0 * M_PI);
  limits.upper[2] = M_PI;
  limits.lower = -limits.upper;
  return limits;
}

inline constexpr double kUr5MaxJointSpeed = M_PI;  ///< rad/s, every joint
/// Joint torque limits (N m): 150 for joints 1-3, 28 for joints 4-6.
inline Joints Ur5TorqueLimits() { return (Joints() << 150, 150, 150, 28, 28, 28).finished(); }

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
