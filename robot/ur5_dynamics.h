#pragma once
/// @file
/// The UR5's own rigid-body dynamics model, as a robot controller keeps one: the links' mass
/// properties from ur_description (the same as models/ur5/ur5.urdf), the motors' rotor inertia and
/// joint friction, and what the flange carries. The planners use it to move as fast as the joint
/// torque limits allow in each pose; tests/sim/ur5_dynamics_test checks it against the simulated arm.

#include <Eigen/Geometry>

#include "robot/ur5_kinematics.h"

namespace sortcell::robot {

/// A rigid body's mass properties in the frame it is fixed to.
struct MassProperties {
  double mass = 0;                                    ///< kg
  Eigen::Vector3d p_com = Eigen::Vector3d::Zero();    ///< centre of mass (m)
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centre of mass (kg m^2)
};

/// Two bodies fixed to the same frame as one (parallel-axis theorem).
MassProperties Combine(const MassProperties& a, const MassProperties& b);

/// The parallel-jaw gripper on the flange (frame F), fingers included (models/gripper).
MassProperties GripperMassProperties();

/// The payload the cell plans for: a point mass (kg) at the TCP.
inline constexpr double kPlannedPayloadKg = 0.5;

class Ur5Dynamics {
 public:
  /// The arm carrying `tool_F` on its flange.
  /// @throws std::invalid_argument for a negative or non-finite mass or centre of mass.
  explicit Ur5Dynamics(const MassProperties& tool_F);

  /// The joint torques (N m) that give accelerations `qdd` at (q, qd): M(q) qdd + C(q, qd) qd + g(q)
  /// by recursive Newton-Euler, plus the rotors' inertia, viscous damping and Coulomb friction (at
  /// qd = 0 friction is taken against the motion qdd asks for, the worst case).
  Joints Torque(const Joints& q, const Joints& qd, const Joints& qdd) const;

  /// Its three parts. Gravity: g(q). Inertial: M(q) qdd + C(q, qd) qd with the rotors' inertia, the
  /// part that falls as 1/k^2 when a motion is slowed down k times in time. Friction: damping and
  /// Coulomb friction.
  Joints Gravity(const Joints& q) const;
  Joints Inertial(const Joints& q, const Joints& qd, const Joints& qdd) const;
  static Joints Friction(const Joints& qd, const Joints& qdd);

  /// Gravity + Inertial: what a controller feeds forward (it leaves friction to its feedback).
  Joints InverseDynamics(const Joints& q, const Joints& qd, const Joints& qdd) const;

 private:
  Joints RigidBodyTorque(const Joints& q, const Joints& qd, const Joints& qdd) const;
  // Links 1..6 (shoulder .. wrist 3, the last with the tool), each in its own frame: D-H frame i-1
  // turned by q_i about its z axis.
  std::array<MassProperties, 6> links_;
};

/// The cell's arm as its planners see it: the gripper and kPlannedPayloadKg at the TCP.
const Ur5Dynamics& CellArmDynamics();

}  // namespace sortcell::robot
