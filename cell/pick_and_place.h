#pragma once
/// @file
/// The pick-and-place sequence of the cell, one attempt, from wherever the last one left the arm:
/// [the first 5 cm out of the last bin slowly, then retreat straight up] -> approach above the object ->
/// descend, one motion without stops, the fingers opening on the way; reach slowly in a straight line;
/// close and squeeze; lift -> carry above the bin -> lower to 5 cm above the release point, again one
/// motion, the hold checked after the lift and above the bin; place slowly; release (wider if something
/// is still caught). The arm stays in the bin: the next attempt (or GoHome) leaves from there.
/// The episode's policy and the scripted `sortcell pick` run this same sequence; they differ in where
/// the grasp (a footprint perceived or read from the scene, its finger clearance) and the release point
/// (a bin slot or the bin's middle, its yaw step) come from.

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "cell/carry_clearance.h"
#include "cell/cell_layout.h"
#include "cell/motion_sequencer.h"
#include "cell/outcomes.h"
#include "robot/grasp_planner.h"

namespace sortcell::cell {

/// Where an attempt left the arm in a bin: the poses straight up out of it.
struct BinExit {
  /// As high as the carry came in: what the camera saw under the next motion is checked from there.
  Eigen::Isometry3d X_WT_low = Eigen::Isometry3d::Identity();
  /// As high as a carry that sees nothing comes in (the held object's bottom
  /// robot::GraspOptions::lift_clearance above the bin's floor, lower where the arm cannot reach that
  /// high): the way out for a motion that is not checked (home, the approach via the grasp plan's lift).
  Eigen::Isometry3d X_WT_high = Eigen::Isometry3d::Identity();
};

struct PickRequest {
  robot::GraspPlan grasp;                                 ///< A plan with status kOk.
  Eigen::Vector3d p_W_release = Eigen::Vector3d::Zero();  ///< The floor point the object is released over.
  double place_yaw_step = CellLayout().place_yaw_step;    ///< Yaws tried for the placement (robot::PlanPlacement).
  double place_yaw_offset = 0;                            ///< The first of them (robot::GraspOptions).
  double release_clearance =
      robot::GraspOptions().release_clearance;    ///< Object bottom above the floor at the release (m).
  robot::Joints q_home = CellLayout().q_observe;  ///< Where the arm goes after a miss or a failure.
  /// Where the last attempt left the arm: it first goes straight up out of the bin; empty: the arm is
  /// free to move (at home).
  std::optional<BinExit> exit;
  ArmSpeeds speeds = CellLayout().speeds;
  /// What the open fingers pass over on the way to the object, as the camera saw it (the object too):
  /// they come over to it no higher than these need. Empty: via the grasp plan's lift.
  std::optional<CarryObstacles> approach_over;
  /// What the carry passes over, as the camera saw it: the lift, the carry and the way down into the
  /// bin go no higher than these need (tried from 0.10 m up). Empty: as high as the grasp plan's lift.
  std::optional<CarryObstacles> carry_over;
  /// How far the held object reaches across from the TCP's axis (m); needed (> 0) with carry_over.
  double held_radius = 0;
};

/// Called at the sequence's milestones, for callers that measure (the scripted pick's slip); the
/// policy needs none.
struct PickHooks {
  std::function<void()> grasped;  ///< The fingers closed and hold something.
  std::function<void()> lifted;   ///< The lift is done.
  std::function<void()> carried;  ///< Above the bin.
  std::function<void()> lowered;  ///< Lowered into the bin, before the release.
  /// Called once during the carry, as soon as `out_of_view(q_commanded)` says the arm and what it
  /// holds no longer hide the workspace from the camera (the policy captures the next view then).
  std::function<bool(const robot::Joints& q)> out_of_view;
  std::function<void()> left_view;
  /// After the fingers closed on the object, before the lift: sets where in the bin to let go (the
  /// request's p_W_release, place_yaw_* and release_clearance) and what the carry passes over
  /// (carry_over), for a caller that looks into the bin first. Without it the request's are used.
  std::function<void(PickRequest& release)> choose_release;
};

struct PickReport {
  AttemptResult result = AttemptResult::kMotionFailed;
  bool grasped = false;      ///< Something held when the fingers closed.
  bool lifted = false;       ///< Still held after the lift.
  bool reached_bin = false;  ///< Carried to the bin and opened there (the slot is used, held or not).
  std::string detail;        ///< Why a motion failed (MotionSequencer::failure()), else empty.
  /// The most of the pads' friction the hold used during the lift and carry (robot::FrictionUse).
  double max_friction_use = 0;
  /// How far off the TCP's axis the fingers found the object's middle when it was grasped again over
  /// it (m, along the TCP's y); 0 when the first grasp was centred.
  double recentred_m = 0;
  /// The phase in which the hold came near slipping and the fingers squeezed harder; empty: never.
  std::string squeezed_harder_in;
  /// Where the arm is to leave to first (straight up out of the bin); empty when it ended at home.
  std::optional<BinExit> exit;
};

/// Runs one attempt. A motion that cannot be planned on the way lets go of whatever is held and
/// goes home (kMotionFailed); a missed grasp or a drop goes home too; a bin that cannot be reached
/// sends the object back to where it was grasped (kPutBack); a fault of the cell ends it at once
/// (kSimDiverged).
/// @throws std::invalid_argument if the request says what the carry passes over (carry_over) but not
/// the held object's reach (held_radius <= 0).
PickReport PickAndPlace(MotionSequencer& run, const PickRequest& request, const PickHooks& hooks = {});

/// From where an attempt left the arm: straight up to `exit`'s high pose (if any), then home, one motion.
bool GoHome(MotionSequencer& run, const std::optional<BinExit>& exit, const robot::Joints& q_home,
            const ArmSpeeds& lines);

}  // namespace sortcell::cell
