#include "cell/motion_sequencer.h"

#include <algorithm>
#include <stdexcept>

#include "robot/time_optimal_timing.h"
#include "robot/torque_limited_motion.h"

namespace sortcell::cell {
namespace {

constexpr double kGripperTimeout = 1.5;   // s, for the fingers to stop
constexpr double kFingersGetGoing = 0.1;  // s, before judging that the fingers stopped
constexpr double kSqueezeTime = 0.2;      // s, for the squeeze to build up
constexpr int kSlowerLines = 3;           // Times a line too fast for a joint is halved in speed.
constexpr int kWatchStride = 10;          // A chain's `when` hook is asked every this many samples (20 ms).
// The arm's least time over a chain is computed every this many samples (10 ms): within 0.1 % of
// every sample's (0.05 % on tests/robot/time_optimal_timing_test.cc's moves), at a fifth of the cost.
constexpr int kBoundStride = 5;

}  // namespace

bool MotionSequencer::Phase(const std::string& name, const std::function<MotionResult()>& action,
                            std::optional<double> bound_s) {
  const double start = io_.Now();
  const MotionResult result = action();
  const robot::GripperSensors fingers = io_.ReadGripper();
  const double end = io_.Now();
  phases_.push_back({name, start, end, robot::DetectHold(fingers), fingers.gap(), bound_s.value_or(end - start)});
  if (result.ok()) return true;
  failure_ = name + ": cell fault: " + result.detail;
  faulted_ = true;
  return false;
}

void MotionChain::Add(const std::string& phase, const robot::JointTrajectory& segment) {
  int seam = 0;
  robot::SampleCheck fits;  // Holding: none, so blends keep joint_limits_' accelerations.
  if (load_ == Load::kEmptyHanded) {
    fits = [budget = robot::TorqueBudget{}](const robot::Joints& q, const robot::Joints& qd, const robot::Joints& qdd) {
      return budget.Fits(q, qd, qdd);
    };
  }
  trajectory_ = robot::BlendMoves(trajectory_, segment, joint_limits_, &seam, fits);
  // The phase before now ends in the middle of the blend (never before the one before it ends).
  if (!phase_ends_.empty()) {
    const int earliest = phase_ends_.size() > 1 ? phase_ends_[phase_ends_.size() - 2].second : 0;
    phase_ends_.back().second = std::max(seam, earliest);
  }
  phase_ends_.emplace_back(phase, trajectory_.size() - 1);
  q_end_ = trajectory_.q.back();
}

bool MotionChain::JointMove(const std::string& phase, const robot::Joints& q_goal) {
  const robot::TorqueLimitedMove move = robot::PlanTorqueLimitedJointMove(q_end_, q_goal, joint_limits_);
  if (move.fit != robot::TorqueFit::kWithinBudget) {
    failure_ = phase + ": the move needs more than the torque budget";
    return false;
  }
  Add(phase, move.trajectory);
  return true;
}

bool MotionChain::Line(const std::string& phase, const Eigen::Isometry3d& X_WT, double speed, double acceleration) {
  robot::CartesianPlan plan = robot::PlanTorqueLimitedLine(q_end_, X_WT, speed, acceleration);
  // Near the edge of the reach a fast line may need a joint faster than pi rad/s: slower then.
  for (int slower = 0; plan.status == robot::CartesianPlanStatus::kTooFast && slower < kSlowerLines; ++slower) {
    speed *= 0.5;
    plan = robot::PlanTorqueLimitedLine(q_end_, X_WT, speed, acceleration);
  }
  if (plan.status != robot::CartesianPlanStatus::kOk) {
    failure_ = phase + ": " + plan.detail;
    return false;
  }
  Add(phase, plan.trajectory);
  return true;
}

bool MotionSequencer::MoveJ(const std::string& name, const robot::Joints& q_goal) {
  MotionChain chain(io_.CommandedJoints(), MotionChain::Load::kHolding);
  chain.JointMove(name, q_goal);
  return Run(chain);
}

bool MotionSequencer::MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed, double acceleration) {
  MotionChain chain(io_.CommandedJoints(), MotionChain::Load::kHolding);
  chain.Line(name, X_WT, speed, acceleration);
  return Run(chain);  // Reports a line that could not be planned.
}

namespace {

// Samples [first, last] of `t` as a trajectory of their own.
robot::JointTrajectory Slice(const robot::JointTrajectory& t, int first, int last) {
  robot::JointTrajectory part;
  part.dt = t.dt;
  part.q.assign(t.q.begin() + first, t.q.begin() + last + 1);
  part.qd.assign(t.qd.begin() + first, t.qd.begin() + last + 1);
  part.qdd.assign(t.qdd.begin() + first, t.qdd.begin() + last + 1);
  return part;
}

// Samples [a, b] of a phase followed, in strides with `watch` after each when there is one.
MotionResult FollowWatched(CellIo& io, const std::string& phase, const robot::JointTrajectory& t, int a, int b,
                           const std::function<void(const std::string&)>& watch) {
  if (!watch) return io.Follow(phase, Slice(t, a, b));
  int k = a;
  do {
    const int next = std::min(k + kWatchStride, b);
    const MotionResult result = io.Follow(phase, Slice(t, k, next));
    if (!result.ok()) return result;
    watch(phase);
    k = next;
  } while (k < b);
  return MotionResult{};
}

// The first sample in [from, last) where `when` holds (asked every kWatchStride samples), else last.
int FirstWhen(const robot::JointTrajectory& t, int from, int last,
              const std::function<bool(const robot::Joints&)>& when) {
  for (int k = from; k < last; k += kWatchStride) {
    if (when(t.q[k])) return k;
  }
  return last;
}

}  // namespace

bool MotionSequencer::Run(const MotionChain& chain, const ChainHooks& hooks) {
  stopped_ = false;
  if (!chain.failure().empty()) {
    failure_ = chain.failure();
    return false;
  }
  const robot::JointTrajectory& t = chain.trajectory();
  if (!t.q.empty() && (t.q.front() - io_.CommandedJoints()).cwiseAbs().maxCoeff() > 1e-6) {
    throw std::logic_error("MotionSequencer::Run: the chain does not start where the arm is held");
  }
  // The least time the arm needs between two samples of the chain; the planned time where the
  // bound cannot be computed (never, for a chain the planner made within the torque budget).
  const robot::PathTiming fastest =
      robot::TimeOptimalTiming(t, robot::Ur5FastLimits().speed, robot::TorqueBudget{}, kBoundStride);
  const auto bound = [&](int a, int b) { return fastest.feasible ? fastest.At(b) - fastest.At(a) : t.dt * (b - a); };
  bool watched = !hooks.when;  // Whether the `when` hook has fired (or there is none).
  int from = 0;
  for (const auto& phase_end : chain.phase_ends()) {
    // Named, not structured bindings: a C++17 lambda cannot capture those (clang refuses).
    const auto& phase = phase_end.first;
    const int last = phase_end.second;
    // The first sample of this phase where `when` holds splits it in two, with `then` in between.
    const int split = watched ? last : FirstWhen(t, from, last, hooks.when);
    const auto follow = [&](int a, int b) { return FollowWatched(io_, phase, t, a, b, hooks.watch); };
    if (!Phase(
            phase, [&] { return follow(from, split); }, bound(from, split)))
      return false;
    if (split < last) {
      watched = true;
      if (hooks.then) hooks.then();
      if (!Phase(
              phase, [&] { return follow(split, last); }, bound(split, last)))
        return false;
    }
    from = last;
    if (hooks.after_phase && !hooks.after_phase(phase)) {
      stopped_ = true;
      failure_ = "stopped after " + phase;
      return false;
    }
  }
  return true;
}

void MotionSequencer::StartFingers(double gap) {
  const double half_gap = robot::HalfGapTarget(gap);
  io_.CommandFingers(half_gap, half_gap);
}

MotionResult MotionSequencer::MoveFingers(const std::string& name, double half_gap) {
  io_.CommandFingers(half_gap, half_gap);
  const double start = io_.Now();
  return io_.HoldUntil(name, kGripperTimeout,
                       [&] { return io_.Now() - start >= kFingersGetGoing && Hold() != robot::HoldState::kMoving; });
}

bool MotionSequencer::Gripper(const std::string& name, double gap) {
  return Phase(name, [&] { return MoveFingers(name, robot::HalfGapTarget(gap)); });
}

MotionResult MotionSequencer::CloseAndSqueeze(const std::string& name) {
  MotionResult result = MoveFingers(name, 0.0);
  if (!result.ok() || Hold() != robot::HoldState::kHolding) return result;
  const auto [left, right] = robot::SqueezeTargets(io_.ReadGripper(), robot::kDefaultGripForce);
  io_.CommandFingers(left, right);
  return io_.Wait(name, kSqueezeTime);
}

bool MotionSequencer::Grasp(const std::string& name) {
  return Phase(name, [&] { return CloseAndSqueeze(name); });
}

bool MotionSequencer::Wait(const std::string& name, double seconds) {
  return Phase(name, [&] { return io_.Wait(name, seconds); });
}

}  // namespace sortcell::cell
