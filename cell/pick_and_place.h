#pragma once
/// @file
/// The pick-and-place sequence of the cell, one attempt: open, approach above the object, descend
/// and reach in straight lines, close and squeeze, check the hold, lift, check again, carry above
/// the bin, lower, release, retreat, home. The episode's policy and the scripted `sortcell pick` run
/// this same sequence; they differ in where the grasp (a footprint perceived or read from the scene,
/// its finger clearance) and the release point (a bin slot or the bin's middle, its yaw step) come from.

#include <functional>
#include <string>

#include <Eigen/Core>

#include "cell/cell_layout.h"
#include "cell/motion_sequencer.h"
#include "cell/outcomes.h"
#include "robot/grasp_planner.h"

namespace sortcell::cell {

struct PickRequest {
  robot::GraspPlan grasp;  ///< A plan with status kOk.
  Eigen::Vector3d p_W_release = Eigen::Vector3d::Zero();  ///< The floor point the object is released over.
  double place_yaw_step = CellLayout().place_yaw_step;    ///< Yaws tried for the placement (robot::PlanPlacement).
  robot::Joints q_home = CellLayout().q_observe;          ///< Where the arm returns afterwards.
  double approach_speed = CellLayout().approach_speed;    ///< The last straight descent onto the object (m/s).
};

/// Called at the sequence's milestones, for callers that measure (the scripted pick's slip); the
/// policy needs none.
struct PickHooks {
  std::function<void()> grasped;  ///< The fingers closed and hold something.
  std::function<void()> lifted;   ///< The lift is done.
  std::function<void()> carried;  ///< Above the bin.
  std::function<void()> lowered;  ///< Lowered into the bin, before the release.
};

struct PickReport {
  AttemptResult result = AttemptResult::kMotionFailed;
  bool grasped = false;  ///< Something held when the fingers closed.
  bool lifted = false;   ///< Still held after the lift.
  bool reached_bin = false;  ///< Carried to the bin and opened there (the slot is used, held or not).
  std::string detail;    ///< Why a motion failed (MotionSequencer::failure()), else empty.
};

/// Runs one attempt. A motion that cannot be planned on the way lets go of whatever is held and
/// goes home (kMotionFailed); a bin that cannot be reached sends the object back to where it was
/// grasped (kPutBack); a fault of the cell ends it at once (kSimDiverged).
PickReport PickAndPlace(MotionSequencer& motions, const PickRequest& request, const PickHooks& hooks = {});

}  // namespace sortcell::cell
