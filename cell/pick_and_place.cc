#include "cell/pick_and_place.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "robot/gripper_geometry.h"
#include "robot/ik_selection.h"
#include "robot/ur5_ik.h"
#include "robot/joint_trajectory.h"

namespace sortcell::cell {
namespace {

// The last part of lowering an object into its bin, slowly (m).
constexpr double kSlowPlacing = 0.05;
// A held object's middle farther than this off the TCP's axis is grasped again over it (m): beyond
// the Kinect's noise in the footprint and the fingers' own play.
constexpr double kOffCentre = 0.006;
// How much wider than the held gap the fingers open to let go (m): 5 mm per side.
constexpr double kReleaseOpening = 0.010;
// A carried object's bottom passes at least this high over what the camera saw under it (m): the
// Kinect's noise at a top (a few mm) and the arm's tracking (mm, cm only where it meets something).
constexpr double kCarryAbove = 0.03;
// ... where it passes within this of it sideways (m).
constexpr double kCarryBeside = 0.02;
// The lowest lift tried (the held object's bottom above where it stood, m), how many tries, and the
// least raise from one to the next (m).
constexpr double kLowestCarry = 0.10;
constexpr int kCarryTries = 8;
constexpr double kCarryRaise = 0.005;

// The gripper as the clearance check sees it from above: the finger tips as far out as the fully open
// fingers' stems reach, and the palm, high above them but wider.
std::vector<HeldObject> GripperParts() {
  return {{robot::kFingerTipBeyondTcp, 0.5 * robot::kMaxGap + robot::kFingerDepth},
          {-robot::kPalmBeforeTcp, robot::kPalmHalfLength}};
}

// The next height to try after one whose path passed `least` (m) over what it came over, where
// kCarryAbove is wanted: as much higher as that needs if the least clearance rises with the height as
// it did from the try before (the path changes with the heights at its ends, so a raise of the ends
// gains less), a quarter of the raise at least; the first time, one for one.
class RaiseToClear {
 public:
  double Next(double height, double least) {
    double gain = 1;
    if (tried_) gain = std::clamp((least - last_least_) / (height - last_height_), 0.25, 1.0);
    tried_ = true;
    last_height_ = height;
    last_least_ = least;
    return height + std::fmax((kCarryAbove - least) / gain, kCarryRaise);
  }

 private:
  bool tried_ = false;
  double last_height_ = 0, last_least_ = 0;
};

void Notify(const std::function<void()>& hook) {
  if (hook) hook();
}

// Home from where the arm is now, after a step failed or the object was lost: straight up to
// `X_WT_up` first, then the joint move.
bool Home(MotionSequencer& run, const PickRequest& request, const Eigen::Isometry3d& X_WT_up) {
  return GoHome(run, BinExit{X_WT_up, X_WT_up}, request.q_home, request.speeds);
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
  if (!run.MoveL("put_back", plan.X_WT_grasp, request.speeds.slow, request.speeds.slow_acceleration) ||
      !run.Gripper("open", plan.open_gap) || !Home(run, request, plan.X_WT_lift)) {
    return Fail(run, request, report);
  }
  report.result = AttemptResult::kPutBack;
  return report;
}

// Over to the object and down to its pre-grasp pose (`approach`, from where it leaves the arm) via the
// lowest pose above the pre-grasp from which the open fingers pass kCarryAbove over everything seen
// under them (the object itself included) off the plumb lines out of the last bin and down to the
// pre-grasp. False: none found below the grasp plan's lift (the caller goes via that).
bool PlanLowApproach(const PickRequest& request, MotionChain& approach) {
  if (!request.approach_over) return false;
  const robot::GraspPlan& plan = request.grasp;
  const ArmSpeeds& lines = request.speeds;
  const robot::GraspOptions grasping;
  const std::vector<HeldObject> gripper = GripperParts();
  std::vector<Eigen::Vector2d> plumb_xy{plan.X_WT_pregrasp.translation().head<2>()};
  if (request.exit) plumb_xy.push_back(request.exit->X_WT_low.translation().head<2>());
  double above = grasping.approach_height;  // The via pose over the pre-grasp (m).
  RaiseToClear raise;
  for (int tries = 0; tries < kCarryTries; ++tries) {
    Eigen::Isometry3d X_WT_via = plan.X_WT_pregrasp;
    X_WT_via.translation().z() += above;
    if (X_WT_via.translation().z() >= plan.X_WT_lift.translation().z()) return false;
    const auto q_via =
        robot::SelectNearest(robot::SolveTcpIk(X_WT_via, plan.q_lift[5]), plan.q_lift, grasping.selection);
    MotionChain trial = approach;
    if (!q_via || std::abs(q_via->q[2]) < grasping.min_elbow_bend || !trial.JointMove("approach", q_via->q) ||
        !trial.Line("descend", plan.X_WT_pregrasp, lines.empty_transit, lines.empty_transit_acceleration)) {
      return false;
    }
    const double least =
        LeastClearanceOver(trial.trajectory(), gripper, *request.approach_over, kCarryBeside, plumb_xy);
    if (least >= kCarryAbove) {
      approach = std::move(trial);
      return true;
    }
    above = raise.Next(above, least);
  }
  return false;
}

// Where the arm was to the fingers closing: out of the last bin, above the object and down to it.
bool ApproachAndGrasp(MotionSequencer& run, const PickRequest& request) {
  const robot::GraspPlan& plan = request.grasp;
  const ArmSpeeds& lines = request.speeds;
  // Out of the bin: the first centimetres slowly, the fingers passing what was just released.
  if (request.exit) {
    Eigen::Isometry3d X_WT_clear = robot::TcpPose(run.io().CommandedJoints());
    X_WT_clear.translation().z() += kSlowPlacing;
    if (!run.MoveL("retreat", X_WT_clear, lines.slow, lines.slow_acceleration)) return false;
  }
  // Up out of the bin as if still holding: what was just released may still touch a finger, and a
  // fast pull flings it out of the bin. Only as high as the carry came in when the way over to the
  // object is checked against what the camera saw; else as high as before, and via the plan's lift.
  const MotionChain start(run.io().CommandedJoints(), MotionChain::Load::kEmptyHanded, lines.empty_joints);
  MotionChain approach = start;
  const bool low =
      (!request.exit || approach.Line("retreat", request.exit->X_WT_low, lines.transit, lines.transit_acceleration)) &&
      PlanLowApproach(request, approach);
  if (!low) {
    approach = start;
    if (request.exit && !approach.Line("retreat", request.exit->X_WT_high, lines.transit, lines.transit_acceleration)) {
      return run.Run(approach);  // Reports the planning failure.
    }
    approach.JointMove("approach", plan.q_lift);
    approach.Line("descend", plan.X_WT_pregrasp, lines.empty_transit, lines.empty_transit_acceleration);
  }
  // The fingers go to the next opening once out of the bin: closing them to a narrower one in it
  // caught an object that had tipped against them and carried it off to the next pick.
  ChainHooks fingers;
  fingers.after_phase = [&](const std::string& phase) {
    if (phase == "retreat") run.StartFingers(plan.open_gap);
    return true;
  };
  if (!request.exit) run.StartFingers(plan.open_gap);
  return run.Run(approach, fingers) && run.MoveL("reach", plan.X_WT_grasp, lines.reach, lines.reach_acceleration) &&
         run.Grasp("grasp");
}

// Nothing held after the fingers closed: open, go home, a miss.
PickReport Missed(MotionSequencer& run, const PickRequest& request, PickReport report) {
  if (!run.Gripper("open", request.grasp.open_gap) || !Home(run, request, request.grasp.X_WT_lift)) {
    return Fail(run, request, report);
  }
  report.grasped = false;
  report.result = AttemptResult::kMissed;
  return report;
}

// A grasp that closed off-centre (one finger met the object first and it did not slide between them):
// opened, moved over where the fingers found its middle, and closed again, once, before the lift,
// which then rises straight from there. False when a motion failed.
bool Recentre(MotionSequencer& run, const ArmSpeeds& lines, robot::GraspPlan& plan, PickReport& report) {
  const double off = robot::HeldOffCentre(run.io().ReadGripper());
  if (std::abs(off) <= kOffCentre) return true;
  const Eigen::Vector3d shift = plan.X_WT_grasp.linear() * Eigen::Vector3d(0, off, 0);
  plan.X_WT_grasp.translation() += shift;
  plan.X_WT_lift.translation() += shift;
  report.recentred_m = off;
  return run.Gripper("regrasp", plan.open_gap) &&
         run.MoveL("recentre", plan.X_WT_grasp, lines.slow, lines.slow_acceleration) && run.Grasp("grasp");
}

// Every 20 ms of the lift and carry: how much of the pads' friction the hold uses; near slipping (the
// accelerations nearly using it up), squeeze harder at once, before the object goes.
void WatchTheGrip(MotionSequencer& run, const std::string& phase, PickReport& report) {
  const robot::GripperSensors fingers = run.io().ReadGripper();
  const double use = robot::FrictionUse(fingers);
  report.max_friction_use = std::max(report.max_friction_use, use);
  if (use > robot::kSlipWarning && report.squeezed_harder_in.empty() &&
      robot::DetectHold(fingers) != robot::HoldState::kEmpty) {
    const auto [left, right] = robot::SqueezeTargets(fingers, robot::kFirmGripForce);
    run.io().CommandFingers(left, right);
    report.squeezed_harder_in = phase;
  }
}

// The last centimetres down into the bin, slowly, and open there. False when a motion failed.
bool LetGo(MotionSequencer& run, const PickRequest& request, const Eigen::Isometry3d& X_WT_release, double release_gap,
           const PickHooks& hooks) {
  const ArmSpeeds& lines = request.speeds;
  if (!run.MoveL("place", X_WT_release, lines.slow, lines.slow_acceleration)) return false;
  Notify(hooks.lowered);
  if (!run.Gripper("release", release_gap)) return false;
  // Still caught by the fingers: open as wide as for the approach, then all the way (an object turned
  // in the grasp may span the fingers corner to corner), or the next motion takes it along.
  for (const double gap : {request.grasp.open_gap, robot::kMaxGap}) {
    if (robot::CaughtAfterOpening(run.io().ReadGripper(), release_gap) && !run.Gripper("release", gap)) return false;
  }
  return true;
}

// Lift to `X_WT_lift`, carry and lower as one chain (`transfer`, starting where the arm is); the
// placement into the bin planned from where the lift ends, the held object's bottom at most
// `place_clearance` above the bin's floor (not ok: the bin cannot be reached from there, the chain
// ends with the lift). False when the lift itself cannot be planned.
bool PlanTransferVia(const PickRequest& release, const Eigen::Isometry3d& X_WT_lift, double place_clearance,
                     MotionChain& transfer, robot::PlacePlan& place) {
  const ArmSpeeds& lines = release.speeds;
  if (!transfer.Line("lift", X_WT_lift, lines.transit, lines.transit_acceleration)) return false;
  robot::GraspOptions place_options;
  // Above the bin at the carry's height (lower only where the arm cannot reach it, down to
  // min_lift_clearance or to it when lower); the walls are the carry's check to clear.
  place_options.lift_clearance = place_clearance;
  place_options.min_lift_clearance = std::fmin(place_options.min_lift_clearance, place_clearance);
  place_options.place_yaw_step = release.place_yaw_step;
  place_options.place_yaw_offset = release.place_yaw_offset;
  place_options.release_clearance = release.release_clearance;
  place = robot::PlanPlacement(release.p_W_release, release.grasp.grasp_height, transfer.end(), place_options);
  if (place.ok) {
    transfer.JointMove("carry", place.q_above);
    // Fast down to just above the release point; the last centimetres (LetGo) are slow.
    Eigen::Isometry3d X_WT_above_release = place.X_WT_release;
    X_WT_above_release.translation().z() += kSlowPlacing;
    transfer.Line("lower", X_WT_above_release, lines.transit, lines.transit_acceleration);
  }
  return true;
}

// The lowest transfer whose held object passes kCarryAbove over everything seen under it once it
// leaves the plumb lines of the lift and of the way down into the bin (the blends' corners included),
// from kLowestCarry up to below the grasp plan's own lift. False: none found (the caller plans the
// grasp plan's).
bool PlanLowTransfer(const PickRequest& release, MotionChain& transfer, robot::PlacePlan& place) {
  if (!(release.held_radius > 0)) {
    throw std::invalid_argument(
        "pick request: what the carry passes over is given but not the held object's reach "
        "(held_radius " +
        std::to_string(release.held_radius) + " m, expected > 0)");
  }
  const robot::GraspPlan& plan = release.grasp;
  std::vector<HeldObject> hanging = GripperParts();  // From the TCP: the gripper and what it holds.
  hanging.push_back({plan.grasp_height, release.held_radius});
  const double grasp_z = plan.X_WT_grasp.translation().z();
  const double bottom_at_grasp_z = grasp_z - plan.grasp_height;
  // Above the bin never lower than where the slow placing starts, with a few millimetres of lowering to it.
  const double lowest_above_bin = release.release_clearance + kSlowPlacing + kCarryRaise;
  double clearance = kLowestCarry;  // The held object's bottom above where it stood (m).
  RaiseToClear raise;
  for (int tries = 0; tries < kCarryTries && grasp_z + clearance < plan.X_WT_lift.translation().z(); ++tries) {
    Eigen::Isometry3d X_WT_lift = plan.X_WT_lift;
    X_WT_lift.translation().z() = std::fmax(grasp_z + clearance, plan.X_WT_pregrasp.translation().z());
    MotionChain trial = transfer;
    robot::PlacePlan trial_place;
    const double place_clearance = std::fmax(bottom_at_grasp_z + clearance - release.p_W_release.z(), lowest_above_bin);
    if (!PlanTransferVia(release, X_WT_lift, place_clearance, trial, trial_place) || !trial_place.ok ||
        trial.phase_ends().back().first != "lower") {
      return false;
    }
    const std::vector<Eigen::Vector2d> plumb_xy{plan.X_WT_grasp.translation().head<2>(),
                                                trial_place.X_WT_release.translation().head<2>()};
    const double least = LeastClearanceOver(trial.trajectory(), hanging, *release.carry_over, kCarryBeside, plumb_xy);
    if (least >= kCarryAbove) {
      transfer = std::move(trial);
      place = trial_place;
      return true;
    }
    clearance = raise.Next(clearance, least);
  }
  return false;
}

// `place`'s pose above the bin, raised to where a carry that sees nothing comes in (the held object's
// bottom lift_clearance above the bin's floor), or to the highest of robot::LiftClearancesHighestFirst below
// that which the arm reaches there in a straight line (as robot::PlanPlacement's way down): the way out of
// the bin for motions not checked against the scene.
Eigen::Isometry3d HighAbove(const robot::PlacePlan& place, const PickRequest& release) {
  const robot::GraspOptions defaults;
  for (const double clearance : robot::LiftClearancesHighestFirst(defaults)) {
    Eigen::Isometry3d X_WT = place.X_WT_above;
    X_WT.translation().z() = release.p_W_release.z() + clearance + release.grasp.grasp_height;
    if (X_WT.translation().z() <= place.X_WT_above.translation().z()) break;
    // The line up from above the bin must plan, its end not near a straight elbow (as PlanPlacement's).
    const robot::CartesianPlan up = robot::PlanCartesianLine(place.q_above, X_WT, robot::kMovelSpeed,
                                                             robot::kMovelAcceleration, 0.002, defaults.selection);
    if (up.status == robot::CartesianPlanStatus::kOk && !up.trajectory.q.empty() &&
        std::abs(up.trajectory.q.back()[2]) >= defaults.min_elbow_bend) {
      return X_WT;
    }
  }
  return place.X_WT_above;
}

// Lift, carry and lower as one chain, as low as what the carry passes over allows (when the request
// says what that is), else as high as the grasp plan's lift.
bool PlanTransfer(const PickRequest& release, MotionChain& transfer, robot::PlacePlan& place) {
  if (release.carry_over && PlanLowTransfer(release, transfer, place)) return true;
  return PlanTransferVia(release, release.grasp.X_WT_lift, robot::GraspOptions().lift_clearance, transfer, place);
}

// What the transfer watches as it runs: the hold after the lift (lost: stop) and above the bin, the
// grip's friction every 20 ms, and when the arm has left the camera's view.
ChainHooks TransferWatch(MotionSequencer& run, const PickHooks& hooks, PickReport& report, bool& held_above_bin) {
  ChainHooks watch;
  watch.after_phase = [&run, &hooks, &report, &held_above_bin](const std::string& phase) {
    if (phase == "lift") {
      Notify(hooks.lifted);
      report.lifted = run.Hold() != robot::HoldState::kEmpty;
      return report.lifted;
    }
    if (phase == "carry") {
      Notify(hooks.carried);
      // Judged above the bin: lowering into it may touch what is already there and move the fingers.
      held_above_bin = run.Hold() != robot::HoldState::kEmpty;
    }
    return true;
  };
  watch.when = hooks.out_of_view;
  watch.then = hooks.left_view;
  watch.watch = [&run, &report](const std::string& phase) { WatchTheGrip(run, phase, report); };
  return watch;
}

}  // namespace

bool GoHome(MotionSequencer& run, const std::optional<BinExit>& exit, const robot::Joints& q_home,
            const ArmSpeeds& lines) {
  MotionChain home(run.io().CommandedJoints(), MotionChain::Load::kEmptyHanded, lines.empty_joints);
  if (exit && !home.Line("retreat", exit->X_WT_high, lines.transit, lines.transit_acceleration)) return run.Run(home);
  home.JointMove("home", q_home);
  return run.Run(home);
}

PickReport PickAndPlace(MotionSequencer& run, const PickRequest& request, const PickHooks& hooks) {
  PickReport report;
  if (!ApproachAndGrasp(run, request)) return Fail(run, request, report);
  if (run.Hold() != robot::HoldState::kHolding) return Missed(run, request, report);
  report.grasped = true;
  PickRequest release = request;  // From here on: the grasp as recentred, the release as chosen.
  if (!Recentre(run, request.speeds, release.grasp, report)) return Fail(run, request, report);
  if (run.Hold() != robot::HoldState::kHolding) return Missed(run, release, report);
  const robot::GraspPlan& plan = release.grasp;
  // Released by opening a little beyond the gap it was held at: in a bin slot near the walls, opening
  // to the approach's wider gap may press a finger against a wall and keep the object.
  const double release_gap = std::fmin(plan.open_gap, run.io().ReadGripper().gap() + kReleaseOpening);
  Notify(hooks.grasped);
  if (hooks.choose_release) hooks.choose_release(release);

  MotionChain transfer(run.io().CommandedJoints(), MotionChain::Load::kHolding, request.speeds.held_joints);
  robot::PlacePlan place;
  if (!PlanTransfer(release, transfer, place)) return Fail(run, request, report);
  bool held_above_bin = false;
  if (!run.Run(transfer, TransferWatch(run, hooks, report, held_above_bin))) {
    if (run.faulted() || !run.stopped()) return Fail(run, request, report);
    // Lost during the lift: let go of nothing and go home, straight up to the grasp plan's lift first
    // (a low lift ends among the neighbours, and the joint move home is checked against nothing).
    const bool home = run.Gripper("open", robot::kMaxGap) && (Home(run, release, release.grasp.X_WT_lift) ||
                                                              (!run.faulted() && run.MoveJ("home", request.q_home)));
    report.result = home ? AttemptResult::kDropped : AttemptResult::kSimDiverged;
    return report;
  }
  if (!place.ok) return PutBack(run, release, report);
  if (!LetGo(run, release, place.X_WT_release, release_gap, hooks)) return Fail(run, request, report);
  report.reached_bin = true;
  report.exit = BinExit{place.X_WT_above, HighAbove(place, release)};
  report.result = held_above_bin ? AttemptResult::kReleased : AttemptResult::kDropped;
  return report;
}

}  // namespace sortcell::cell
