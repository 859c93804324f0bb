#include "robot/joint_trajectory.h"

#include <cmath>
#include <stdexcept>

#include "robot/ur5_ik.h"

namespace sortcell::robot {
namespace {

// Rotation counts into a Cartesian line's length at this many metres per radian, so that a pure
// reorientation also gets a duration.
constexpr double kMetresPerRadian = 0.1;

void CheckMotionParameters(const char* what, double speed, double acceleration, double dt) {
  if (!(speed > 0) || !(acceleration > 0) || !(dt > 0) || !std::isfinite(speed) || !std::isfinite(acceleration)) {
    throw std::invalid_argument(std::string(what) + ": speed, acceleration and dt must be positive (got " +
                                std::to_string(speed) + ", " + std::to_string(acceleration) + ", " +
                                std::to_string(dt) + ")");
  }
}

}  // namespace

void JointTrajectory::Append(const JointTrajectory& other) {
  if (other.q.empty()) return;
  if (q.empty()) {
    *this = other;
    return;
  }
  if (std::abs(other.dt - dt) > 1e-12) throw std::invalid_argument("JointTrajectory::Append: different dt");
  if ((other.q.front() - q.back()).cwiseAbs().maxCoeff() > 1e-6) {
    throw std::invalid_argument("JointTrajectory::Append: segments do not join");
  }
  q.insert(q.end(), other.q.begin() + 1, other.q.end());
  qd.insert(qd.end(), other.qd.begin() + 1, other.qd.end());
  qdd.insert(qdd.end(), other.qdd.begin() + 1, other.qdd.end());
}

TrapezoidProfile::TrapezoidProfile(double distance, double speed, double acceleration)
    : distance_(std::abs(distance)), speed_(speed), acceleration_(acceleration) {
  if (distance_ * acceleration_ < speed_ * speed_) {
    // Triangle: accelerate to the middle and brake.
    t_ramp_ = std::sqrt(distance_ / acceleration_);
    speed_ = acceleration_ * t_ramp_;
    duration_ = 2.0 * t_ramp_;
  } else {
    t_ramp_ = speed_ / acceleration_;
    duration_ = distance_ / speed_ + t_ramp_;
  }
}

void TrapezoidProfile::Evaluate(double t, double& s, double& sd, double& sdd) const {
  t = std::fmax(0.0, std::fmin(t, duration_));
  if (t < t_ramp_) {
    s = 0.5 * acceleration_ * t * t;
    sd = acceleration_ * t;
    sdd = acceleration_;
  } else if (t <= duration_ - t_ramp_) {
    s = 0.5 * acceleration_ * t_ramp_ * t_ramp_ + speed_ * (t - t_ramp_);
    sd = speed_;
    sdd = 0;
  } else {
    const double r = duration_ - t;
    s = distance_ - 0.5 * acceleration_ * r * r;
    sd = acceleration_ * r;
    sdd = -acceleration_;
  }
  if (t >= duration_) sd = sdd = 0;
}

JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, double speed, double acceleration,
                              double dt) {
  CheckMotionParameters("joint move", speed, acceleration, dt);
  if (speed > kUr5MaxJointSpeed + 1e-12) {
    throw std::invalid_argument("joint move: speed " + std::to_string(speed) + " rad/s exceeds the UR5 limit of pi");
  }
  if (!q_start.allFinite() || !q_goal.allFinite()) throw std::invalid_argument("joint move: non-finite joints");
  const Joints delta = q_goal - q_start;
  const double distance = delta.cwiseAbs().maxCoeff();
  const Joints direction = distance > 0 ? Joints(delta / distance) : Joints::Zero();
  const TrapezoidProfile profile(distance, speed, acceleration);
  const int steps = static_cast<int>(std::ceil(profile.duration() / dt - 1e-9));

  JointTrajectory trajectory;
  trajectory.dt = dt;
  for (int k = 0; k <= steps; ++k) {
    double s, sd, sdd;
    profile.Evaluate(k * dt, s, sd, sdd);
    trajectory.q.push_back(k == steps ? q_goal : Joints(q_start + s * direction));
    trajectory.qd.push_back(sd * direction);
    trajectory.qdd.push_back(sdd * direction);
  }
  return trajectory;
}

CartesianPlan PlanCartesianLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed,
                                double acceleration, double dt, const SelectionOptions& selection) {
  CheckMotionParameters("Cartesian line", speed, acceleration, dt);
  CartesianPlan plan;
  const Eigen::Isometry3d X_BT_start = TcpPose(q_start);
  const Eigen::Vector3d p0 = X_BT_start.translation(), p1 = X_BT_goal.translation();
  const Eigen::Quaterniond r0(X_BT_start.linear()), r1(X_BT_goal.linear());
  const double length = std::fmax((p1 - p0).norm(), kMetresPerRadian * r0.angularDistance(r1));
  const TrapezoidProfile profile(length, speed, acceleration);
  const int steps = static_cast<int>(std::ceil(profile.duration() / dt - 1e-9));

  JointTrajectory& trajectory = plan.trajectory;
  trajectory.dt = dt;
  Joints q_previous = q_start;
  for (int k = 0; k <= steps; ++k) {
    double s, sd, sdd;
    profile.Evaluate(k * dt, s, sd, sdd);
    const double u = length > 0 ? (k == steps ? 1.0 : s / length) : 1.0;
    Eigen::Isometry3d X_BT = Eigen::Isometry3d::Identity();
    X_BT.translation() = p0 + u * (p1 - p0);
    X_BT.linear() = r0.slerp(u, r1).toRotationMatrix();
    const IkResult ik = SolveTcpIk(X_BT, q_previous[5]);
    const auto chosen = SelectNearest(ik, q_previous, selection);
    if (!chosen) {
      plan.status = CartesianPlanStatus::kUnreachable;
      plan.detail = "no valid IK solution at " + std::to_string(u * 100).substr(0, 5) + " % of the line";
      return plan;
    }
    if (k > 0 && ((chosen->q - q_previous).cwiseAbs().maxCoeff() > kUr5MaxJointSpeed * dt)) {
      plan.status = CartesianPlanStatus::kTooFast;
      plan.detail = "a joint would exceed pi rad/s at " + std::to_string(u * 100).substr(0, 5) + " % of the line";
      return plan;
    }
    trajectory.q.push_back(chosen->q);
    q_previous = chosen->q;
  }
  // Velocities and accelerations by central differences; zero at both ends (the line starts and
  // ends at rest).
  const int n = trajectory.size();
  trajectory.qd.assign(n, Joints::Zero());
  trajectory.qdd.assign(n, Joints::Zero());
  for (int k = 1; k + 1 < n; ++k) {
    trajectory.qd[k] = (trajectory.q[k + 1] - trajectory.q[k - 1]) / (2 * dt);
    trajectory.qdd[k] = (trajectory.q[k + 1] - 2 * trajectory.q[k] + trajectory.q[k - 1]) / (dt * dt);
  }
  plan.status = CartesianPlanStatus::kOk;
  return plan;
}

}  // namespace sortcell::robot
