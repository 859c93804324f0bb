#include "cell/pick_choice.h"

#include <algorithm>
#include <tuple>

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

PickChoice ChoosePick(const std::vector<Detection>& detections, robot::PickMemory& memory, const FixedObstacles& fixed,
                      const robot::Joints& q_near) {
  PickChoice choice;
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
      grasp = ClearestGraspOf(detections, i, fixed.p_xy, fixed.top_z);
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
      if (freest == blocked.end()) return choice;
      std::tie(i, grasp) = *freest;
      blocked.erase(freest);
      if (view.Skipped(footprints[i].centre_xy) != robot::SkipReason::kNone) continue;  // Given up meanwhile.
    }
    // The IK branch nearest to q_near (the observe pose: the natural one for picking), wherever the arm is now.
    robot::GraspOptions options = GraspOptionsFor(grasp.footprint, detections[i].lying);
    options.min_tcp_z = grasp.min_tcp_z;
    choice.plan = robot::PlanTopDownGrasp(grasp.footprint, q_near, options);
    if (choice.plan.status == robot::GraspStatus::kOk) {
      choice.detection = i;
      return choice;
    }
    for (robot::PickMemory* m : {&memory, &view, &unhidden, &free, &free_hidden}) {
      m->Skip(footprints[i].centre_xy, robot::SkipReason::kUnreachable);
    }
    choice.unplannable.emplace_back(i, choice.plan.status);
  }
}

}  // namespace sortcell::cell
