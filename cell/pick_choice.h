#pragma once
/// @file
/// Which detection the sorting loop picks next, and how: the one pick-choice module. Of the described
/// clusters not given up (robot::PickMemory), the one with the most room around it (robot::ChooseNextPick),
/// pinched the way whose open fingers clear its neighbours and the bins' walls (robot::ClearestGrasp); one
/// partly hidden behind another, or whose fingers would land on a neighbour, waits until nothing else is
/// left. A cluster with no grasp plan is given up as unreachable; one too small to describe is never picked.

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cell/scene_observation.h"
#include "robot/grasp_planner.h"
#include "robot/pick_selection.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// What open fingers must keep clear of besides the objects: the bins' wall outlines (world xy, m), as
/// high as the walls reach (world z, m).
struct FixedObstacles {
  std::vector<Eigen::Vector2d> p_xy;
  double top_z = 0;
};

struct PickChoice {
  int detection = -1;     ///< Index into the detections; -1: nothing left that can be picked.
  robot::GraspPlan plan;  ///< Its grasp, planned from the IK branch nearest `q_near`.
  /// Detections given up on the way for want of a grasp plan, in the order they were (with why).
  std::vector<std::pair<int, robot::GraspStatus>> unplannable;
};

/// The detection to pick next and its grasp plan. Detections without a plan are given up in `memory`.
PickChoice ChoosePick(const std::vector<Detection>& detections, robot::PickMemory& memory, const FixedObstacles& fixed,
                      const robot::Joints& q_near);

}  // namespace sortcell::cell
