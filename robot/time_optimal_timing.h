#pragma once
/// @file
/// The fastest traversal of a given joint path (time-optimal path parametrisation): how soon the arm
/// could run the very path a trajectory follows, from rest to rest, moving as hard as its joint speed
/// and torque (or acceleration) limits allow at every point. The cell reports its pick cycle against
/// this lower bound, phase by phase.
///
/// Method: TOPP-RA (Pham and Pham, "A new approach to time-optimal path parameterization based on
/// reachability analysis", IEEE T-RO 2018). The path is parametrised by the trajectory's own time s;
/// at each sample the joint velocity is q'(s) sdot and the acceleration q'(s) sddot + q''(s) sdot^2, so
/// every limit is linear in (x, u) = (sdot^2, sddot). A backward pass finds at each sample the x from
/// which the end can still be reached, a forward pass then takes the largest u that stays inside them.
/// Written here because no Debian package offers it (TOPP-RA itself is a pip package).

#include <vector>

#include "robot/joint_trajectory.h"
#include "robot/torque_limited_motion.h"

namespace sortcell::robot {

/// When the samples of a path are reached at the fastest.
struct PathTiming {
  /// False where the limits cannot be kept somewhere on the path even creeping through it (e.g. the
  /// arm's weight alone over the torque budget); the times are then empty.
  bool feasible = false;
  std::vector<int> samples;  ///< The path's samples the timing was computed at: every stride-th and the last.
  std::vector<double> t;     ///< When each of them is reached (s); t[0] = 0.

  double duration() const { return t.empty() ? 0.0 : t.back(); }
  /// When the path's sample k is reached (s), linear between the computed samples; k is clamped to
  /// the path.
  double At(int k) const;
};

/// The fastest timing of `path` (its q, qd, qdd as planned; it starts and ends at rest) under per-joint
/// speed and acceleration limits, computed at every `stride`-th sample.
/// @throws std::invalid_argument for stride < 1, a non-positive dt, or non-positive limits.
PathTiming TimeOptimalTiming(const JointTrajectory& path, const JointMotionLimits& limits, int stride = 1);

/// The same under per-joint speed limits and a torque budget (the dynamics model's torque within
/// budget.fraction of budget.limits). Friction is bounded by its value at the speed limit instead of
/// following the speed, so the result stays a lower bound for every motion that keeps the budget.
/// @throws std::invalid_argument as above.
PathTiming TimeOptimalTiming(const JointTrajectory& path, const Joints& speed, const TorqueBudget& budget,
                             int stride = 1);

}  // namespace sortcell::robot
