#include "cell/pick_and_place.h"

#include "robot/gripper_geometry.h"
#include "robot/joint_trajectory.h"

namespace sortcell::cell {
namespace {

void Notify(const std::function<void()>& hook) {
  if (hook) hook();
}

// The sequence after a step failed: a fault ends it; a motion that could not be planned lets go of
// whatever is held and goes back to observe.
PickReport Fail(MotionSequencer& run, const PickRequest& request, PickReport report) {
  report.detail = run.failure();
  if (run.faulted()) {
    report.result = AttemptResult::kSimDiverged;
    return report;
  }
  const bool recovered = run.Gripper("open", robot::kMaxGap) && run.MoveJ("home", request.q_home);
  report.result = recovered ? AttemptResult::kMotionFailed : AttemptResult::kSimDiverged;
  return report;
}

// The lifted object's bin cannot be reached from here: put it back down where it was grasped.
PickReport PutBack(MotionSequencer& run, const PickRequest& request, PickReport report) {
  const robot::GraspPlan& plan = request.grasp;
  if (!run.MoveL("put_back", plan.X_WT_grasp, robot::kMovelSpeed)) return Fail(run, request, report);
  if (!run.Gripper("open", plan.open_gap) || !run.MoveL("retreat", plan.X_WT_lift, robot::kMovelSpeed) ||
      !run.MoveJ("home", request.q_home)) {
    return Fail(run, request, report);
  }
  report.result = AttemptResult::kPutBack;
  return report;
}

}  // namespace

PickReport PickAndPlace(MotionSequencer& run, const PickRequest& request, const PickHooks& hooks) {
  const robot::GraspPlan& plan = request.grasp;
  PickReport report;
  if (!run.Gripper("open", plan.open_gap) || !run.MoveJ("approach", plan.q_lift) ||
      !run.MoveL("descend", plan.X_WT_pregrasp, robot::kMovelSpeed) ||
      !run.MoveL("reach", plan.X_WT_grasp, request.approach_speed) || !run.Grasp("grasp")) {
    return Fail(run, request, report);
  }
  if (run.Hold() != robot::HoldState::kHolding) {
    if (!run.Gripper("open", plan.open_gap) || !run.MoveL("retreat", plan.X_WT_lift, robot::kMovelSpeed) ||
        !run.MoveJ("home", request.q_home)) {
      return Fail(run, request, report);
    }
    report.result = AttemptResult::kMissed;
    return report;
  }
  report.grasped = true;
  Notify(hooks.grasped);
  if (!run.MoveL("lift", plan.X_WT_lift, robot::kMovelSpeed)) return Fail(run, request, report);
  Notify(hooks.lifted);
  if (run.Hold() == robot::HoldState::kEmpty) {
    const bool home = run.Gripper("open", robot::kMaxGap) && run.MoveJ("home", request.q_home);
    report.result = home ? AttemptResult::kDropped : AttemptResult::kSimDiverged;
    return report;
  }
  report.lifted = true;

  robot::GraspOptions place_options;
  place_options.place_yaw_step = request.place_yaw_step;
  const robot::PlacePlan place =
      robot::PlanPlacement(request.p_W_release, plan.grasp_height, run.io().CommandedJoints(), place_options);
  if (!place.ok) return PutBack(run, request, report);
  if (!run.MoveJ("carry", place.q_above)) return Fail(run, request, report);
  Notify(hooks.carried);
  // Judged above the bin: lowering into it may touch what is already there and move the fingers.
  const bool held = run.Hold() != robot::HoldState::kEmpty;
  if (!run.MoveL("lower", place.X_WT_release, robot::kMovelSpeed)) return Fail(run, request, report);
  Notify(hooks.lowered);
  if (!run.Gripper("release", plan.open_gap) || !run.MoveL("retreat", place.X_WT_above, robot::kMovelSpeed) ||
      !run.MoveJ("home", request.q_home)) {
    return Fail(run, request, report);
  }
  report.reached_bin = true;
  report.result = held ? AttemptResult::kReleased : AttemptResult::kDropped;
  return report;
}

}  // namespace sortcell::cell
