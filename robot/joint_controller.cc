#include "robot/joint_controller.h"

#include <cmath>
#include <stdexcept>

namespace sortcell::robot {

PdGains DefaultUr5Gains() {
  PdGains gains;
  gains.kp << 3000, 3000, 2000, 300, 300, 100;
  gains.kd << 150, 150, 80, 10, 10, 3;
  return gains;
}

double TrackingStats::rms_error() const { return samples > 0 ? std::sqrt(sum_sq_error / (6.0 * samples)) : 0.0; }

JointController::JointController(const PdGains& gains, const Joints& torque_limits)
    : gains_(gains), limits_(torque_limits) {
  if (!gains.kp.allFinite() || !gains.kd.allFinite() || !torque_limits.allFinite() || gains.kp.minCoeff() < 0 ||
      gains.kd.minCoeff() < 0 || torque_limits.minCoeff() <= 0) {
    throw std::invalid_argument("JointController: gains must be finite and >= 0, torque limits > 0");
  }
}

Joints JointController::Torque(const Joints& q, const Joints& qd, const Joints& q_ref, const Joints& qd_ref,
                               const Joints& feed_forward) {
  const Joints error = q_ref - q;
  Joints tau = gains_.kp.cwiseProduct(error) + gains_.kd.cwiseProduct(qd_ref - qd) + feed_forward;
  const Joints clamped = tau.cwiseMax(-limits_).cwiseMin(limits_);
  stats_.max_error = std::fmax(stats_.max_error, error.cwiseAbs().maxCoeff());
  stats_.sum_sq_error += error.squaredNorm();
  ++stats_.samples;
  if (clamped != tau) ++stats_.saturated_samples;
  return clamped;
}

}  // namespace sortcell::robot
