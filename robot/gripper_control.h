#pragma once
/// @file
/// Gripper commands and hold detection. The gripper's finger servos are force-limited in the model
/// (60 N per finger); the robot layer chooses targets and judges, from the finger encoders and the
/// pads' contact forces, whether something is held.

#include "robot/gripper_geometry.h"

namespace sortcell::robot {

/// What the gripper's sensors report.
struct GripperSensors {
  double left_half_gap = 0;   ///< Finger joint positions (m): pad surface to the TCP plane.
  double right_half_gap = 0;
  double left_speed = 0;      ///< Finger joint speeds (m/s).
  double right_speed = 0;
  double left_pad_force = 0;  ///< Normal contact force on each finger's pads (N).
  double right_pad_force = 0;
  double gap() const { return left_half_gap + right_half_gap; }
};

enum class HoldState {
  kMoving,   ///< Fingers still travelling: not yet decided.
  kEmpty,    ///< Closed on nothing (fingers at the stop, or no pad contact).
  kHolding,  ///< Both fingers stopped on something and squeeze it.
};

struct HoldDetection {
  double min_gap = 0.004;           ///< A gap below this is "closed on nothing" (m).
  double min_pad_force = 5.0;       ///< Each side must squeeze with at least this much (N).
  double settled_speed = 0.002;     ///< Fingers slower than this have stopped (m/s).
};

/// Judges the hold from one sensor reading.
HoldState DetectHold(const GripperSensors& sensors, const HoldDetection& detection = {});

const char* ToString(HoldState state);

/// After opening to `gap`: whether the fingers stopped more than `tolerance` short of it or anything
/// presses on a pad with at least `min_force` (N), i.e. something is still caught by the fingers.
bool CaughtAfterOpening(const GripperSensors& sensors, double gap, double tolerance = 0.002, double min_force = 0.5);

/// Half-gap target (m) for opening to `gap` (m), clamped to the stroke.
double HalfGapTarget(double gap);

/// Squeezing what the fingers closed on: each finger's target is set `grip_force / kFingerServoKp`
/// inside where it stopped. Closing against a target of 0 saturates both servos at their force limit,
/// which makes them two equal and opposite force sources: the held object and both fingers can then
/// drift together along the closing axis under any sideways acceleration (measured: 2-3 mm over a
/// carry). Unsaturated, each finger is a spring to its own target and the pair resists that drift
/// with 2 kp = 4000 N/m. @pre grip_force in (0, kFingerForceLimit).
double SqueezeTarget(double half_gap_at_contact, double grip_force);

/// The default grip force per finger (N): with mu = 1.5 on two pads it holds 90 N of load, ~25x the
/// heaviest object's weight (0.35 kg), with headroom for the carry's accelerations.
inline constexpr double kDefaultGripForce = 30;

}  // namespace sortcell::robot
