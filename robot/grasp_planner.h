#pragma once
/// @file
/// Top-down grasp planning for the parallel gripper from what is known of an object: where it
/// stands, how tall it is and along which horizontal direction it is narrowest. The same planner
/// serves the scripted `sortcell pick` (footprint from the scene file) and the perception-driven
/// episode (footprint from a segmented cloud).

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "robot/ik_selection.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::robot {

/// An object standing on the table, in the world (= Base) frame.
struct ObjectFootprint {
  Eigen::Vector2d centre_xy;  ///< Centre of the part to grasp, on the table (m).
  double base_z = 0;          ///< Height of its lowest point (m).
  double top_z = 0;           ///< Height of its highest point (m).
  double pinch_yaw = 0;       ///< Horizontal direction across which it is narrowest (rad).
  double width = 0;           ///< Its extent along pinch_yaw (m): what the fingers close on.
  /// Up to this height it is nearly as wide as `width` (world z, m): a grasp raised above a neighbour
  /// goes no higher (a bottle's shoulder, not its neck; a ball's middle, not its top).
  double full_width_top_z = INFINITY;
};

struct GraspOptions {
  double finger_clearance = 0.0045;  ///< Per side, between open pads and the object (m).
  double palm_clearance = 0.015;     ///< Between the object's top and the palm (m).
  /// The lowest TCP height the neighbours leave the gripper's body (world z, m; a taller neighbour
  /// under the palm or the housing): the grasp rises to it, but the TCP stays min_pad_overlap (m) below
  /// the object's top and no higher than its full_width_top_z.
  double min_tcp_z = -INFINITY;
  double min_pad_overlap = 0.02;
  double table_clearance = 0.010;  ///< Between finger tips and the table (m).
  double approach_height = 0.03;   ///< Finger tips above the object's top where the slow descent starts (m).
  /// Lift the object's bottom this high above the table before carrying it anywhere (m): above the
  /// tallest objects of the sets (0.224 m bottles) and the bins' 0.10 m walls.
  double lift_clearance = 0.30;
  /// Where the arm cannot reach that high (the workspace's far corners), the lift is lowered in
  /// 2 cm steps down to this clearance, still above the bins' walls (m).
  double min_lift_clearance = 0.15;
  /// The elbow bent at least this much (|q3|, rad) at the lift and pre-grasp poses: near a straight
  /// elbow (a singularity) the straight lines through them need joints faster than pi rad/s.
  double min_elbow_bend = 0.15;
  /// At release, the object's bottom this high above the bin floor (m).
  double release_clearance = 0.03;
  /// Yaws tried for the placement, in steps of this (rad); pi/2 keeps a held box square to the bin.
  double place_yaw_step = M_PI / 8;
  /// The first of those yaws (rad): pi/4 with steps of pi/2 lays a long held object (a lying bottle,
  /// held across its axis) along the bin's diagonal, the only way it fits.
  double place_yaw_offset = 0;
  SelectionOptions selection;
};

enum class GraspStatus { kOk, kTooWide, kTooLow, kUnreachable };
const char* ToString(GraspStatus status);

struct GraspPlan {
  GraspStatus status = GraspStatus::kUnreachable;
  Eigen::Isometry3d X_WT_pregrasp = Eigen::Isometry3d::Identity();  ///< Above the grasp, fingers open.
  Eigen::Isometry3d X_WT_grasp = Eigen::Isometry3d::Identity();     ///< Pads around the object.
  Eigen::Isometry3d X_WT_lift = Eigen::Isometry3d::Identity();      ///< Straight above, object lifted.
  Joints q_lift = Joints::Zero();  ///< IK of the lift pose nearest to the current joints: the arm
                                   ///< arrives there first (above everything) and descends in lines.
  double open_gap = 0;             ///< Gap to open to before the descent (m).
  double grasp_height = 0;         ///< TCP height above the object's base (m).
};

/// The TCP's height above the object's base for a top-down grasp of `object` (PlanTopDownGrasp's):
/// its middle, raised until the palm clears its top and to options.min_tcp_z (as far as the pads still
/// overlap it and it is still full width), the finger tips above the table.
double GraspHeight(const ObjectFootprint& object, const GraspOptions& options);

/// The clearances (m) a lift or a placement tries, highest first: options.lift_clearance, then 2 cm lower
/// each, the last the lowest of those steps not below options.min_lift_clearance (0.30 to 0.16 with the
/// defaults).
std::vector<double> LiftClearancesHighestFirst(const GraspOptions& options);

/// A top-down TCP pose (z_T pointing down) at p_W whose fingers close along `pinch_yaw`.
Eigen::Isometry3d TopDownTcpPose(const Eigen::Vector3d& p_W, double pinch_yaw);

/// Plans lift, pre-grasp and grasp poses for `object` (approach: lift -> pre-grasp -> grasp in
/// straight lines; retreat: back to lift). Of the two equivalent yaws (pinch_yaw and pinch_yaw + pi),
/// takes the one whose lift-pose IK lies nearer to `q_current`. The grasp height is the object's middle,
/// raised if needed so the palm clears its top (and to min_tcp_z). Expected failures are statuses: too
/// wide for the stroke, too flat to hold, or no valid IK for a pose on the way.
GraspPlan PlanTopDownGrasp(const ObjectFootprint& object, const Joints& q_current, const GraspOptions& options = {});

struct PlacePlan {
  bool ok = false;
  Eigen::Isometry3d X_WT_above = Eigen::Isometry3d::Identity();    ///< Above the bin, object clear of the walls.
  Eigen::Isometry3d X_WT_release = Eigen::Isometry3d::Identity();  ///< Lowered into the bin.
  Joints q_above = Joints::Zero();
};

/// Placing a held object (grasped `grasp_height` above its bottom) into a bin whose floor centre is
/// p_W_floor: the highest reachable top-down pose above it between the lift clearances (yaws in steps of
/// place_yaw_step, nearest IK to q_current first) from which the straight line down, until the object's
/// bottom is release_clearance above the floor, is reachable and smooth (no joint faster than pi rad/s
/// at the default line speed: no change of IK branch on the way); the nearest reachable one if no line
/// is smooth.
PlacePlan PlanPlacement(const Eigen::Vector3d& p_W_floor, double grasp_height, const Joints& q_current,
                        const GraspOptions& options = {});

/// The top-down TCP pose at p_W (any yaw yaw_offset + k yaw_step) whose valid IK lies nearest to
/// q_current; false if none is reachable.
bool NearestTopDownPose(const Eigen::Vector3d& p_W, const Joints& q_current, const SelectionOptions& selection,
                        Eigen::Isometry3d& X_WT, Joints& q, double yaw_step = M_PI / 8, double yaw_offset = 0);

}  // namespace sortcell::robot
