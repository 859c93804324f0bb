#pragma once
/// @file
/// What the sorting cell knows of itself, in one place: the arm's observe pose, where the bins are and
/// how they are filled, the workspace the camera watches, the table, the speeds of the careful
/// motions and the control period. The bins and the rules that fill them are the user's (a cell file,
/// scenes/cells/*.yaml, read by files/cell_file.h); the table comes from the scene
/// (simcell/sim_layout.h); everything else is fixed here.

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cell/sorting_rules.h"
#include "robot/gripper_geometry.h"
#include "robot/joint_trajectory.h"
#include "robot/ur5_limits.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// How fast the arm moves. Holding an object it keeps to moderate caps, so the grasp holds; with empty
/// fingers only the joint torques limit it. Lines and joint moves are planned at these caps and slowed
/// down where the pose needs it (robot/torque_limited_motion.h): every motion is torque-checked. What
/// each cap was measured against: docs/performance.md, "Motion".
struct ArmSpeeds {
  /// Holding an object, where the fingers touch nothing else (the lift, down into a bin): speed (m/s)
  /// and peak acceleration (m/s^2).
  /// (At 5 m/s^2 a sim test lost a user's block held at the limit of its pads' friction; at 4, in one of two runs.)
  double transit = 0.8;
  double transit_acceleration = 3.0;
  /// Holding, the carry over to the bin: half as hard again as the accelerations that are within the
  /// torque budget in every pose (robot::Ur5AccelerationLimits), slowed where a pose needs it.
  robot::JointMotionLimits held_joints{robot::Joints::Constant(robot::kUr5MaxJointSpeed),
                                       1.5 * robot::Ur5AccelerationLimits()};
  /// With empty fingers: to above the next object and down to it, and home.
  double empty_transit = 1.0;
  double empty_transit_acceleration = 8.0;
  robot::JointMotionLimits empty_joints{robot::Joints::Constant(robot::kUr5MaxJointSpeed),
                                        (robot::Joints() << 25, 25, 25, 40, 40, 40).finished()};
  /// The last descent onto an object, the fingers passing its sides: no faster (blended into the descent
  /// and faster, a finger pushed a cluttered neighbour and the grasp missed), but up to speed sooner (at
  /// 2 m/s^2 the descent was mostly speeding up and slowing down).
  double reach = 0.25;
  double reach_acceleration = 6.0;
  /// Slow: the last centimetres into a bin (holding, at 4 m/s^2: the sweeps and a grasp at its friction
  /// limit kept their objects there) and the first out of it, the recentring, and the put-back (holding,
  /// rare: not measured on its own at these caps).
  double slow = 0.3;
  double slow_acceleration = 4.0;
};

/// A bin as the cell knows it (the world's x and y are its sides).
struct Bin {
  Eigen::Vector3d p_W_floor = Eigen::Vector3d::Zero();           ///< The centre of its floor (m).
  Eigen::Vector2d inner_half = Eigen::Vector2d::Constant(0.10);  ///< Half its inside along x and y (m).
};

struct CellLayout {
  /// The arm's home (= observe) pose: tool down, upper arm leaning back, TCP at (0.281, 0.109, 0.446),
  /// above and behind the workspace's near edge, where no ray from the Kinect to the table or an
  /// object passes (those rays are below the table there), and high enough that every transit starts
  /// above the tallest objects. The IK branch nearest to it (shoulder facing the workspace, elbow up)
  /// is the natural one for picking.
  robot::Joints q_observe = (robot::Joints() << M_PI, -1.9, 1.3, -M_PI_2 + 0.6, -M_PI_2, 0).finished();
  /// Half of the finger gap at the observe pose (m): fully open.
  double observe_half_gap = robot::kMaxGap / 2;

  /// The bins, by name: open boxes standing on the table, walls bin_wall_height high and
  /// bin_wall_thickness thick around their inside.
  std::map<std::string, Bin> bins;
  /// Which bin each recognised object goes into.
  SortingRules rules;
  /// Where released objects go in a bin, in order: its corners, then the middle, so a bin takes four
  /// objects without dropping one onto another. Each is a direction from the floor's centre (signs
  /// along x and y); a corner slot's centre stays bin_slot_inset from the walls. (In a larger bin the
  /// corner slots move apart: in a 0.26 m bin, slots half way to the walls put an upright bottle on the
  /// edge of one lying across the middle, and it toppled out over the wall.)
  std::vector<Eigen::Vector2d> bin_slots{{-1, -1}, {1, 1}, {-1, 1}, {1, -1}, {0, 0}};
  double bin_slot_inset = 0.05;
  /// Held objects are released square to the bin: placement yaws in steps of this (rad).
  double place_yaw_step = M_PI / 2;
  /// Every bin's walls (m). An object longer than a bin is wide goes in along the diagonal, in the
  /// middle, let go above the walls.
  double bin_wall_height = 0.10;
  double bin_wall_thickness = 0.008;

  /// The pick area the camera watches (world box, m): the table in front of the robot up to its far
  /// edge (objects out of reach there are seen and reported unreachable), between the bins, up to
  /// above the tallest objects (0.224 m bottles). The arm must neither hide it nor be in it when the
  /// camera captures (WorkspaceView).
  Eigen::Vector3d workspace_min_W{0.28, -0.34, -0.05};
  Eigen::Vector3d workspace_max_W{0.88, 0.34, 0.28};
  /// The table top (z = 0), x and y extent (m).
  Eigen::Vector2d table_min_xy{-0.3, -0.7};
  Eigen::Vector2d table_max_xy{0.9, 0.7};

  /// The arm's speeds.
  ArmSpeeds speeds;
  /// The arm controller's period (s): 500 Hz.
  double control_period = 0.002;
};

/// The bin named `bin`.
/// @throws std::invalid_argument naming it if the layout has none.
const Bin& BinNamed(const CellLayout& layout, const std::string& bin);
/// The bin slot for the `filled`-th object released into `bin` (cycling through the slots).
/// @throws std::invalid_argument naming the bin if the layout has none of that name.
Eigen::Vector3d BinSlot(const CellLayout& layout, const std::string& bin, int filled);

/// The bins' walls seen from above (world xy, m): their inner and outer outlines every `spacing`.
/// What open fingers must keep clear of besides the objects: one landing on a wall is stopped there.
std::vector<Eigen::Vector2d> BinWallOutlines(const CellLayout& layout, double spacing = 0.005);

}  // namespace sortcell::cell
