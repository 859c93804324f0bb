#pragma once
/// @file
/// Gripper commands and hold detection. The gripper's finger servos are force-limited in the model
/// (60 N per finger); the robot layer chooses targets and judges, from the finger encoders and the
/// pads' contact forces, whether something is held.

#include <utility>

#include "robot/gripper_geometry.h"

namespace sortcell::robot {

/// What the gripper's sensors report.
struct GripperSensors {
  double left_half_gap = 0;  ///< Finger joint positions (m): pad surface to the TCP plane.
  double right_half_gap = 0;
  double left_speed = 0;  ///< Finger joint speeds (m/s).
  double right_speed = 0;
  double left_pad_force = 0;  ///< Normal contact force on each finger's pads (N).
  double right_pad_force = 0;
  double left_pad_shear = 0;  ///< Tangential contact force on each finger's pads (N).
  double right_pad_shear = 0;
  double left_pad_twist = 0;  ///< Torsional moment about the pads' normals (N m).
  double right_pad_twist = 0;
  double gap() const { return left_half_gap + right_half_gap; }
};

enum class HoldState {
  kMoving,   ///< Fingers still travelling: not yet decided.
  kEmpty,    ///< Closed on nothing (fingers at the stop, or no pad contact).
  kHolding,  ///< Both fingers stopped on something and squeeze it.
};

struct HoldDetection {
  double min_gap = 0.004;        ///< A gap below this is "closed on nothing" (m).
  double min_pad_force = 5.0;    ///< Each side must squeeze with at least this much (N).
  double settled_speed = 0.002;  ///< Fingers slower than this have stopped (m/s).
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

/// How much of the pads' friction a hold uses (0: none, 1: at the edge of slipping): the larger of
/// the two fingers' sqrt((shear / mu)^2 + (twist / mu_twist)^2) / normal force, with the pads' own
/// friction (kPadFriction, kPadTwistFriction: the pads' material sets every pad contact's friction).
/// 0 without pad contact.
double FrictionUse(const GripperSensors& sensors);

/// Where what the fingers hold sits off the TCP's axis along the closing direction y (m): the middle
/// between the pads, (left half gap - right half gap) / 2 (the left finger is on +y).
inline double HeldOffCentre(const GripperSensors& sensors) {
  return 0.5 * (sensors.left_half_gap - sensors.right_half_gap);
}

/// Half-gap targets that squeeze what the fingers hold now with `grip_force` per finger (SqueezeTarget
/// of each finger's present position).
std::pair<double, double> SqueezeTargets(const GripperSensors& sensors, double grip_force);

/// The grip force per finger once a hold is seen near slipping (N): below the servos' 60 N limit, so
/// they stay springs (SqueezeTarget). A servo's target cannot pass the closed stop (0), so an object
/// narrower than 2 x 50 N / kFingerServoKp = 50 mm is squeezed with kFingerServoKp x its half width.
inline constexpr double kFirmGripForce = 50;
/// A hold using more than this share of its friction is near slipping: squeeze harder.
inline constexpr double kSlipWarning = 0.6;

/// The default grip force per finger (N): with mu = 1.5 on two pads it holds 90 N of load, ~25x the
/// heaviest object's weight (0.35 kg), with headroom for the carry's accelerations.
inline constexpr double kDefaultGripForce = 30;

}  // namespace sortcell::robot
