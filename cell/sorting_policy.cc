#include "cell/sorting_policy.h"

#include <algorithm>
#include <chrono>
#include <tuple>
#include <utility>
#include <stdexcept>

#include "cell/layout_check.h"
#include "perception/seconds_since.h"
#include "robot/gripper_geometry.h"

namespace sortcell::cell {
namespace {

// Finger clearance per side for a perceived width (Kinect noise ~2 mm at 1 m), reduced down to the
// planner's default (the scripted pick's 4.5 mm) when the object is that close to the stroke.
constexpr double kPerceivedClearance = 0.008;
const double kMinClearance = robot::GraspOptions().finger_clearance;

// Open fingers this far from every neighbour are free to come down (m): beyond the Kinect's noise.
constexpr double kFreeFingers = 0.004;

// A lying object's middle across its axis is the least certain (its far side is hidden, its neighbours
// hide more of it), and a finger landing on it rolls it away: more room per side where the stroke allows.
constexpr double kLyingClearance = 0.015;

robot::GraspOptions GraspOptionsFor(const robot::ObjectFootprint& object, bool lying) {
  robot::GraspOptions options;
  const double wanted = lying ? kLyingClearance : kPerceivedClearance;
  options.finger_clearance = std::max(kMinClearance, std::min(wanted, 0.5 * (robot::kMaxGap - object.width)));
  return options;
}

// What a held object reaches across from the TCP's axis (m): half the largest finger gap (whatever
// fitted between the fingers, and the sets' 0.09 m boxes along them), or as far as its points were
// from the grasp centre: a lying bottle's ends, 0.11 m out, were seen in a bin as 0.36 m high contents.
double HeldReach(const Detection& d) {
  double reach = 0.5 * robot::kMaxGap;
  for (const Eigen::Vector2d& p : d.p_W_xy) reach = std::max(reach, (p - d.footprint.centre_xy).norm());
  return reach;
}

// Everything seen but detection `target`, as obstacles of the fingers and the gripper's body; the
// bins' walls (fixed_xy) reach wall_top_z.
robot::Neighbours NeighboursOf(const std::vector<Detection>& detections, size_t target,
                               const std::vector<Eigen::Vector2d>& fixed_xy, double wall_top_z) {
  robot::Neighbours neighbours;
  neighbours.p_xy = fixed_xy;
  neighbours.p_z.assign(fixed_xy.size(), wall_top_z);
  for (size_t j = 0; j < detections.size(); ++j) {
    if (j == target) continue;
    const Detection& d = detections[j];
    neighbours.p_xy.insert(neighbours.p_xy.end(), d.p_W_xy.begin(), d.p_W_xy.end());
    neighbours.p_z.insert(neighbours.p_z.end(), d.p_W_z.begin(), d.p_W_z.end());
    neighbours.discs.emplace_back(d.footprint.centre_xy, 0.5 * d.footprint.width);
    neighbours.disc_top_z.push_back(d.footprint.top_z);
  }
  return neighbours;
}

// The ways detection `i` may be pinched (round: from any side; a prism: across either pair of sides;
// lying: across its axis), the one whose open fingers clear the neighbours, with the height its body needs.
robot::ClearGrasp ClearestGraspOf(const std::vector<Detection>& detections, size_t i,
                                  const std::vector<Eigen::Vector2d>& fixed_xy, double wall_top_z) {
  const Detection& d = detections[i];
  std::vector<robot::ObjectFootprint> ways{d.footprint};
  if (d.round) ways = robot::RoundWays(d.footprint);
  if (d.turned) ways.push_back(*d.turned);
  std::vector<double> side_clearances;  // As the grasp will open for each (GraspOptionsFor).
  for (const auto& way : ways) side_clearances.push_back(GraspOptionsFor(way, d.lying).finger_clearance);
  return robot::ClearestGrasp(ways, side_clearances, NeighboursOf(detections, i, fixed_xy, wall_top_z));
}

}  // namespace

SortingPolicy::SortingPolicy(CellIo& io, const CellLayout& layout, const CameraCalibration& calibration,
                             const perception::RecognitionModel& model, const PolicyOptions& options,
                             PolicyObserver* observer)
    : io_(io),
      layout_(layout),
      calibration_(calibration),
      model_(model),
      options_(options),
      observer_(observer ? *observer : no_observer_),
      motions_(io),
      segmentation_(CellSegmentation(layout)),
      view_(calibration, layout.workspace_min_W, layout.workspace_max_W),
      bins_(layout),
      bin_walls_xy_(BinWallOutlines(layout)) {
  if (options.max_attempts_per_position < 1 || options.max_attempts < 1) {
    throw std::invalid_argument("policy options: attempt limits must be at least 1");
  }
  if (!(options.time_limit_s > 0)) throw std::invalid_argument("policy options: time limit must be > 0 s");
  CheckRules(layout, model.classes);
}

Observation SortingPolicy::Observe(const std::optional<HeldObject>& held) {
  observer_.Observing();
  const perception::Cloud::Ptr cloud = io_.Capture();
  const auto start = std::chrono::steady_clock::now();
  Observation observation = ObserveScene(*cloud, calibration_, segmentation_, model_);
  bins_.See(*cloud, calibration_.X_WC, ArmCapsules(io_.ReadJoints(), held));
  unseen_release_.reset();
  for (Detection& d : observation.detections) {
    if (d.category) d.bin = *layout_.rules.BinFor(*d.category, d.confidence);  // Every class has one (CheckRules).
  }
  observer_.Observed(*cloud, observation, perception::SecondsSince(start));
  return observation;
}

void SortingPolicy::LookIntoBins(const HeldObject& held) {
  bins_.See(*io_.Capture(), calibration_.X_WC, ArmCapsules(io_.ReadJoints(), held));
  unseen_release_.reset();
}

BinRelease SortingPolicy::ChooseRelease(const Detection& seen, int filled, double min_clearance) const {
  if (seen.lying) return bins_.Lying(seen.bin);
  // Upright it stands on its footprint: across the pinch and, for a prism, its other pair of sides.
  const double across = seen.turned ? seen.turned->width : seen.footprint.width;
  const double radius = 0.5 * std::hypot(seen.footprint.width, seen.round ? 0.0 : across);
  return bins_.Upright(seen.bin, filled, radius, min_clearance);
}

int SortingPolicy::Choose(const std::vector<Detection>& detections, robot::PickMemory& memory, robot::GraspPlan& plan) {
  // Candidates: every described cluster; the undescribed ones still count as neighbours.
  std::vector<robot::ObjectFootprint> footprints;
  for (const auto& d : detections) footprints.push_back(d.footprint);
  robot::PickMemory view = memory;  // This capture's view: undescribed clusters are never picked.
  for (const auto& d : detections) {
    if (!d.category) view.Skip(d.footprint.centre_xy, robot::SkipReason::kUnreachable);
  }
  // An object partly hidden behind another waits until that one has gone, and so does one whose open
  // fingers would land on a neighbour (blocked): picking the others changes the scene. When nothing
  // else is left, the best of them is tried.
  robot::PickMemory unhidden = view;
  for (const auto& d : detections) {
    if (d.occluded) unhidden.Skip(d.footprint.centre_xy, robot::SkipReason::kUnreachable);
  }
  robot::PickMemory free = unhidden, free_hidden = view;
  // Blocked candidates with their freest grasp, tried freest first when no free one is left.
  std::vector<std::pair<int, robot::ClearGrasp>> blocked;
  while (true) {
    int i = robot::ChooseNextPick(footprints, free);
    if (i < 0) i = robot::ChooseNextPick(footprints, free_hidden);
    robot::ClearGrasp grasp;
    if (i >= 0) {
      grasp = ClearestGraspOf(detections, i, bin_walls_xy_, layout_.bin_wall_height);
      if (grasp.clearance < kFreeFingers) {
        for (robot::PickMemory* m : {&free, &free_hidden})
          m->Skip(footprints[i].centre_xy, robot::SkipReason::kUnreachable);
        blocked.emplace_back(i, grasp);
        continue;
      }
    } else {
      const auto freest = std::max_element(blocked.begin(), blocked.end(), [](const auto& a, const auto& b) {
        return a.second.clearance < b.second.clearance;
      });
      if (freest == blocked.end()) return -1;
      std::tie(i, grasp) = *freest;
      blocked.erase(freest);
      if (view.Skipped(footprints[i].centre_xy) != robot::SkipReason::kNone) continue;  // Given up meanwhile.
    }
    // The IK branch nearest to the observe pose (the natural one for picking), wherever the arm is now.
    robot::GraspOptions options = GraspOptionsFor(grasp.footprint, detections[i].lying);
    options.min_tcp_z = grasp.min_tcp_z;
    plan = robot::PlanTopDownGrasp(grasp.footprint, layout_.q_observe, options);
    if (plan.status == robot::GraspStatus::kOk) return i;
    for (robot::PickMemory* m : {&memory, &view, &unhidden, &free, &free_hidden}) {
      m->Skip(footprints[i].centre_xy, robot::SkipReason::kUnreachable);
    }
    observer_.Skipped(i, detections[i], plan.status);
  }
}

AttemptReport SortingPolicy::Attempt(const Detection& seen, int index, int attempt, const robot::GraspPlan& plan,
                                     const std::optional<Eigen::Isometry3d>& X_WT_exit,
                                     std::optional<Observation>& next_view) {
  AttemptReport report;
  report.detection = index;
  report.seen = &seen;
  report.attempt = attempt;
  report.start_s = io_.Now();
  observer_.AttemptStarting(report);
  int& filled = released_into_[seen.bin];
  PickRequest request;
  request.grasp = plan;
  request.q_home = layout_.q_observe;
  request.X_WT_exit = X_WT_exit;
  request.speeds = layout_.speeds;
  PickHooks hooks;
  const HeldObject held{plan.grasp_height, HeldReach(seen)};
  hooks.out_of_view = [&](const robot::Joints& q) { return !view_.ArmInView(q, held); };
  hooks.left_view = [&] { next_view = Observe(held); };
  hooks.grasped = [&] { observer_.Grasped(); };
  hooks.lowered = [&] { observer_.Lowered(); };
  hooks.choose_release = [&](PickRequest& placing) {
    // The last release into this bin has not been seen yet: look, while the fingers squeeze.
    if (unseen_release_ == seen.bin) LookIntoBins(held);
    report.release = ChooseRelease(seen, filled, placing.release_clearance);
    placing.p_W_release = report.release.p_W_floor;
    placing.place_yaw_step = report.release.yaw_step;
    placing.place_yaw_offset = report.release.yaw_offset;
    placing.release_clearance = report.release.clearance;
  };
  const size_t first_phase = motions_.phases().size();
  report.pick = PickAndPlace(motions_, request, hooks);
  report.phases.assign(motions_.phases().begin() + first_phase, motions_.phases().end());
  if (report.pick.reached_bin) {
    ++filled;
    bins_.Released(seen.bin, report.release, seen.footprint.top_z - seen.footprint.base_z);
    unseen_release_ = seen.bin;
  }
  report.end_s = io_.Now();
  observer_.AttemptEnded(report);
  return report;
}

PolicyResult SortingPolicy::Run() {
  PolicyResult result;
  const double start = io_.Now();
  robot::PickMemory memory(options_.same_object_radius, options_.max_attempts_per_position);
  std::optional<Observation> during_carry;     // The view captured during the last carry.
  std::optional<Eigen::Isometry3d> X_WT_exit;  // Where the arm is to leave to first (out of a bin).
  while (!motions_.faulted()) {
    if (io_.Now() - start >= options_.time_limit_s) {
      result.status = EpisodeStatus::kTimeLimit;
      break;
    }
    if (result.attempts >= options_.max_attempts) {
      result.status = EpisodeStatus::kAttemptLimit;
      break;
    }
    Observation observation;
    if (during_carry) {
      observation = std::move(*during_carry);
      during_carry.reset();
    } else {
      // The arm may hide the view: home first.
      if (X_WT_exit && !GoHome(motions_, X_WT_exit, layout_.q_observe, layout_.speeds)) break;
      X_WT_exit.reset();
      observation = Observe();
    }
    ++result.frames;
    robot::GraspPlan plan;
    const int chosen = Choose(observation.detections, memory, plan);
    if (chosen < 0) break;  // Nothing left that can be picked.
    const Detection& seen = observation.detections[chosen];
    const int attempt = memory.RecordAttempt(seen.footprint.centre_xy);
    ++result.attempts;
    const AttemptReport report = Attempt(seen, chosen, attempt, plan, X_WT_exit, during_carry);
    X_WT_exit = report.pick.X_WT_exit;
    const AttemptResult r = report.pick.result;
    // Only a release into the bin leaves the view captured during the carry as it was.
    if (r != AttemptResult::kReleased) during_carry.reset();
    if (r == AttemptResult::kMotionFailed || r == AttemptResult::kPutBack) {
      memory.Skip(seen.footprint.centre_xy, robot::SkipReason::kUnreachable);
    }
    if (r == AttemptResult::kSimDiverged) break;
  }
  // Home at the end, out of the bin the last object went into.
  if (!motions_.faulted() && X_WT_exit) GoHome(motions_, X_WT_exit, layout_.q_observe, layout_.speeds);
  if (motions_.faulted()) result.status = EpisodeStatus::kSimDiverged;
  return result;
}

}  // namespace sortcell::cell
