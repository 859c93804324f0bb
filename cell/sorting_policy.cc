#include "cell/sorting_policy.h"

#include <algorithm>
#include <chrono>
#include <utility>
#include <stdexcept>

#include "cell/layout_check.h"
#include "common/wall_clock.h"
#include "robot/gripper_geometry.h"

namespace sortcell::cell {
namespace {

// What a held object reaches across from the TCP's axis (m): half the largest finger gap (whatever
// fitted between the fingers, and the sets' 0.09 m boxes along them), or as far as its points were
// from the grasp centre: a lying bottle's ends, 0.11 m out, were seen in a bin as 0.36 m high contents.
double HeldReach(const Detection& d) {
  double reach = 0.5 * robot::kMaxGap;
  for (const Eigen::Vector2d& p : d.p_W_xy) reach = std::max(reach, (p - d.footprint.centre_xy).norm());
  return reach;
}

// What the arm passes over, as the camera saw it: every object seen but `held` (-1: none), as the
// disc its points cover up to its top, and every bin, its walls included, up to them or to what it holds.
CarryObstacles PassedOver(const std::vector<Detection>& detections, int held, const CellLayout& layout,
                          const BinFill& bins) {
  CarryObstacles over;
  for (int i = 0; i < static_cast<int>(detections.size()); ++i) {
    if (i == held) continue;
    const Detection& d = detections[i];
    double radius = 0.5 * d.footprint.width;
    for (const Eigen::Vector2d& p : d.p_W_xy) radius = std::max(radius, (p - d.footprint.centre_xy).norm());
    over.discs.push_back({d.footprint.centre_xy, radius, d.footprint.top_z});
  }
  for (const auto& [name, bin] : layout.bins) {
    const Eigen::Vector2d half = bin.inner_half + Eigen::Vector2d::Constant(layout.bin_wall_thickness);
    const Eigen::Vector2d centre = bin.p_W_floor.head<2>();
    over.boxes.push_back(
        {centre - half, centre + half, bin.p_W_floor.z() + std::max(layout.bin_wall_height, bins.HighestIn(name))});
  }
  return over;
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
      bin_walls_{BinWallOutlines(layout), layout.bin_wall_height} {
  if (options.pick.max_attempts_per_position < 1 || options.max_attempts < 1) {
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
  observer_.Observed(*cloud, observation, SecondsSince(start));
  return observation;
}

void SortingPolicy::LookIntoBins(const HeldObject& held) {
  bins_.See(*io_.Capture(), calibration_.X_WC, ArmCapsules(io_.ReadJoints(), held));
  unseen_release_.reset();
}

BinRelease SortingPolicy::ChooseRelease(const Detection& seen, int filled, double min_clearance,
                                        double grasp_height) const {
  if (seen.lying) return bins_.Lying(seen.bin);
  // Upright it stands on its footprint: across the pinch and, for a prism, its other pair of sides.
  const double across = seen.turned ? seen.turned->width : seen.footprint.width;
  const double radius = 0.5 * std::hypot(seen.footprint.width, seen.round ? 0.0 : across);
  // A slot the arm can let this object go in, held this high above its bottom, as robot::PlanPlacement
  // plans it (a tall bottle held high cannot be let down into a bin's far corner: the layout's check
  // holds for objects held 5 cm above their bottom).
  const auto placeable = [&](const BinRelease& release) {
    robot::GraspOptions options;
    options.place_yaw_step = release.yaw_step;
    options.place_yaw_offset = release.yaw_offset;
    options.release_clearance = release.clearance;
    return robot::PlanPlacement(release.p_W_floor, grasp_height, layout_.q_observe, options).ok;
  };
  return bins_.Upright(seen.bin, filled, radius, min_clearance, placeable);
}

AttemptReport SortingPolicy::Attempt(const std::vector<Detection>& detections, int index, int attempt,
                                     const robot::GraspPlan& plan, const std::optional<BinExit>& exit,
                                     std::optional<Observation>& next_view) {
  const Detection& seen = detections[index];
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
  request.exit = exit;
  request.speeds = layout_.speeds;
  PickHooks hooks;
  const HeldObject held{plan.grasp_height, HeldReach(seen)};
  request.held_radius = held.radius;
  request.approach_over = PassedOver(detections, -1, layout_, bins_);
  hooks.out_of_view = [&](const robot::Joints& q) { return !view_.ArmInView(q, held); };
  hooks.left_view = [&] { next_view = Observe(held); };
  hooks.grasped = [&] { observer_.Grasped(); };
  hooks.lowered = [&] { observer_.Lowered(); };
  hooks.choose_release = [&](PickRequest& placing) {
    // The last release into this bin has not been seen yet: look, while the fingers squeeze.
    if (unseen_release_ == seen.bin) LookIntoBins(held);
    report.release = ChooseRelease(seen, filled, placing.release_clearance, placing.grasp.grasp_height);
    placing.p_W_release = report.release.p_W_floor;
    placing.place_yaw_step = report.release.yaw_step;
    placing.place_yaw_offset = report.release.yaw_offset;
    placing.release_clearance = report.release.clearance;
    placing.carry_over = PassedOver(detections, index, layout_, bins_);
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
  robot::PickMemory memory(options_.pick);
  std::optional<Observation> during_carry;  // The view captured during the last carry.
  std::optional<BinExit> exit;              // Where the arm is to leave to first (out of a bin).
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
      if (exit && !GoHome(motions_, exit, layout_.q_observe, layout_.speeds)) break;
      exit.reset();
      observation = Observe();
    }
    ++result.frames;
    const PickChoice choice = ChoosePick(observation.detections, memory, bin_walls_, layout_.q_observe);
    for (const auto& [i, why] : choice.unplannable) observer_.Skipped(i, observation.detections[i], why);
    if (choice.detection < 0) break;  // Nothing left that can be picked.
    const int chosen = choice.detection;
    const Detection& seen = observation.detections[chosen];
    const int attempt = memory.RecordAttempt(seen.footprint.centre_xy);
    ++result.attempts;
    const AttemptReport report = Attempt(observation.detections, chosen, attempt, choice.plan, exit, during_carry);
    exit = report.pick.exit;
    const AttemptResult r = report.pick.result;
    // Only a release into the bin leaves the view captured during the carry as it was.
    if (r != AttemptResult::kReleased) during_carry.reset();
    if (r == AttemptResult::kMotionFailed || r == AttemptResult::kPutBack) {
      memory.Skip(seen.footprint.centre_xy, robot::SkipReason::kUnreachable);
    }
    if (r == AttemptResult::kSimDiverged) break;
  }
  // Home at the end, out of the bin the last object went into.
  if (!motions_.faulted() && exit) GoHome(motions_, exit, layout_.q_observe, layout_.speeds);
  if (motions_.faulted()) result.status = EpisodeStatus::kSimDiverged;
  return result;
}

}  // namespace sortcell::cell
