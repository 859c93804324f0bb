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

/// Half-gap target (m) for opening to `gap` (m), clamped to the stroke.
double HalfGapTarget(double gap);

}  // namespace sortcell::robot
