#pragma once
/// @file
/// The arm's joint controller: PD on the tracking error plus a feed-forward torque (supplied by the
/// caller from its dynamics model: gravity, Coriolis and the reference's inertia, e.g.
/// Ur5Dynamics::InverseDynamics), saturated at the UR5's joint torque limits. Allocation-free, for
/// the fixed-rate control loop.

#include "robot/ur5_kinematics.h"
#include "robot/ur5_limits.h"

namespace sortcell::robot {

struct PdGains {
  Joints kp;  ///< N m / rad
  Joints kd;  ///< N m s / rad
};

/// Gains tuned on the simulated UR5 with the gripper (models/ur5, models/gripper) at a 500 Hz control
/// rate: roughly critically damped, stiff enough to hold a 0.35 kg object within ~1 mrad.
PdGains DefaultUr5Gains();

/// Tracking error statistics over a run (rad).
struct TrackingStats {
  double max_error = 0;     ///< Largest |q_ref - q| over all joints and samples.
  double sum_sq_error = 0;  ///< Sum over samples of |q_ref - q|^2 (all joints).
  long samples = 0;
  int saturated_samples = 0;  ///< Samples where some joint hit its torque limit.
  double rms_error() const;
};

class JointController {
 public:
  /// @throws std::invalid_argument for negative or non-finite gains or limits.
  explicit JointController(const PdGains& gains = DefaultUr5Gains(), const Joints& torque_limits = Ur5TorqueLimits());

  /// tau = clamp(kp (q_ref - q) + kd (qd_ref - qd) + feed_forward, +-limit). Updates the tracking
  /// statistics.
  Joints Torque(const Joints& q, const Joints& qd, const Joints& q_ref, const Joints& qd_ref,
                const Joints& feed_forward);

  const TrackingStats& stats() const { return stats_; }
  void ResetStats() { stats_ = {}; }

 private:
  PdGains gains_;
  Joints limits_;
  TrackingStats stats_;
};

}  // namespace sortcell::robot
