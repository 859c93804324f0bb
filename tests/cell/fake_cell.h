#pragma once
// A scripted cell for the policy's unit tests: clouds from a list (the last one repeats), an arm that
// arrives wherever it is sent, a clock that advances by what each motion takes, and a gripper whose
// closing either holds the object or closes on nothing, as each scripted grasp says.
#include <deque>
#include <string>
#include <vector>

#include "cell/cell_io.h"
#include "robot/gripper_geometry.h"

namespace sortcell_test {

class FakeCell : public sortcell::cell::CellIo {
 public:
  // What the next closings of the fingers find: true = an object (held until the fingers open).
  std::deque<bool> grasps;
  // Where the object's middle sits off the TCP's axis (along its y, m) at each closing on it that
  // finds one; none left: centred.
  std::deque<double> grasp_offsets;
  // Lose the held object during the lift (the next "lift" motion).
  bool drop_on_lift = false;
  // The held object starts to slip as the carry begins: the pads' friction nearly used up (shear at
  // 90 % of what the default squeeze holds); unless the fingers squeeze harder within 60 ms of the
  // carry, it is lost.
  bool slip_on_carry = false;
  std::vector<sortcell::perception::Cloud::Ptr> clouds;
  int captures = 0;
  std::vector<std::string> motions;                  // Phase of every Follow, in order (a phase's parts as one).
  std::vector<sortcell::robot::Joints> motion_ends;  // Where each of them left the arm.
  std::string fault_on;                              // The cell stops under the first motion of this phase.

  // The clock starts at `start_s`, not 0: budgets count from the policy's start.
  explicit FakeCell(const sortcell::robot::Joints& q, double start_s = 100.0) : q_(q), now_(start_s) {
    Open(0.055, 0.055);
  }

  sortcell::perception::Cloud::Ptr Capture() override {
    const size_t i = std::min<size_t>(captures++, clouds.size() - 1);
    return clouds[i];
  }
  sortcell::robot::Joints ReadJoints() const override { return q_; }
  sortcell::robot::Joints CommandedJoints() const override { return q_; }
  sortcell::robot::GripperSensors ReadGripper() const override { return sensors_; }

  sortcell::cell::MotionResult Follow(std::string_view phase, const sortcell::robot::JointTrajectory& t) override {
    // A phase followed in parts (the policy watching between them) is one motion here.
    const bool continues = !motions.empty() && motions.back() == phase;
    if (!continues) motions.emplace_back(phase);
    if (!fault_on.empty() && phase == fault_on) return {sortcell::cell::MotionStatus::kFault, "diverged (scripted)"};
    if (t.size() > 0) q_ = t.q.back();
    if (continues) {
      motion_ends.back() = q_;
    } else {
      motion_ends.push_back(q_);
    }
    now_ += t.duration();
    if (phase == "lift" && drop_on_lift && holding_) Open(0.0, 0.0);
    if (phase == "carry" && slip_on_carry && holding_) Slip(t.duration());
    return {};
  }
  void CommandFingers(double left, double right) override {
    if (left == 0 && right == 0) {  // Closing on whatever is between the fingers (a squeeze may aim past 0).
      const bool object = !grasps.empty() && grasps.front();
      if (!grasps.empty()) grasps.pop_front();
      holding_ = object;
      sensors_ = {};
      if (object) {
        const double off = grasp_offsets.empty() ? 0.0 : grasp_offsets.front();
        if (!grasp_offsets.empty()) grasp_offsets.pop_front();
        sensors_.left_half_gap = 0.02 + off, sensors_.right_half_gap = 0.02 - off;
        sensors_.left_pad_force = sensors_.right_pad_force = 20;
      }
    } else if (holding_ && left < sensors_.left_half_gap) {  // Squeezing what is held: springs to the targets.
      sensors_.left_pad_force = sortcell::robot::kFingerServoKp * (sensors_.left_half_gap - left);
      sensors_.right_pad_force = sortcell::robot::kFingerServoKp * (sensors_.right_half_gap - right);
    } else {
      Open(left, right);
    }
  }
  sortcell::cell::MotionResult HoldUntil(std::string_view, double max_seconds,
                                         const std::function<bool()>& done) override {
    const double start = now_;
    while (now_ - start < max_seconds) {
      now_ += 0.002;
      if (done()) break;
    }
    return {};
  }
  sortcell::cell::MotionResult Wait(std::string_view, double seconds) override {
    now_ += seconds;
    return {};
  }
  double Now() const override { return now_; }

 private:
  void Slip(double seconds) {
    constexpr double kDefaultSqueeze = 30;
    slipping_s_ += seconds;
    sensors_.left_pad_shear = sensors_.right_pad_shear = 0.9 * sortcell::robot::kPadFriction * kDefaultSqueeze;
    if (sensors_.left_pad_force < 1.5 * kDefaultSqueeze && slipping_s_ > 0.06) Open(0.0, 0.0);
  }
  void Open(double left, double right) {
    holding_ = false;
    sensors_ = {};
    sensors_.left_half_gap = left;
    sensors_.right_half_gap = right;
  }

  sortcell::robot::Joints q_;
  sortcell::robot::GripperSensors sensors_;
  bool holding_ = false;
  double slipping_s_ = 0;
  double now_;
};

}  // namespace sortcell_test
