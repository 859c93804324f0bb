#include "robot/gripper_control.h"

#include <cmath>

#include "common/enum_names.h"

namespace sortcell::robot {

HoldState DetectHold(const GripperSensors& s, const HoldDetection& d) {
  if (std::abs(s.left_speed) > d.settled_speed || std::abs(s.right_speed) > d.settled_speed) return HoldState::kMoving;
  if (s.gap() < d.min_gap) return HoldState::kEmpty;
  if (s.left_pad_force < d.min_pad_force || s.right_pad_force < d.min_pad_force) return HoldState::kEmpty;
  return HoldState::kHolding;
}

constexpr EnumNames<HoldState, 3> kHoldStateNames{
    {{HoldState::kMoving, "moving"}, {HoldState::kEmpty, "empty"}, {HoldState::kHolding, "holding"}}};

const char* ToString(HoldState state) { return NameOf(kHoldStateNames, state); }

bool CaughtAfterOpening(const GripperSensors& s, double gap, double tolerance, double min_force) {
  return s.gap() < std::fmin(gap, kMaxGap) - tolerance || s.left_pad_force >= min_force ||
         s.right_pad_force >= min_force;
}

double SqueezeTarget(double half_gap_at_contact, double grip_force) {
  return half_gap_at_contact - grip_force / kFingerServoKp;
}

double FrictionUse(const GripperSensors& s) {
  const auto side = [](double normal, double shear, double twist) {
    if (normal <= 0) return 0.0;
    return std::hypot(shear / kPadFriction, twist / kPadTwistFriction) / normal;
  };
  return std::fmax(side(s.left_pad_force, s.left_pad_shear, s.left_pad_twist),
                   side(s.right_pad_force, s.right_pad_shear, s.right_pad_twist));
}

std::pair<double, double> SqueezeTargets(const GripperSensors& sensors, double grip_force) {
  return {SqueezeTarget(sensors.left_half_gap, grip_force), SqueezeTarget(sensors.right_half_gap, grip_force)};
}

double HalfGapTarget(double gap) { return std::fmax(0.0, std::fmin(0.5 * gap, 0.5 * kMaxGap)); }

}  // namespace sortcell::robot
