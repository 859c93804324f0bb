#include "robot/joint_trajectory.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

SmoothProfile::SmoothProfile(double distance, double speed, double acceleration)
    : distance_(std::abs(distance)), speed_(speed) {
  // A ramp from rest to speed V with a(t) = A sin^2(pi t / T) takes T = 2 V / A and covers V T / 2 =
  // V^2 / A; two of them must fit into the distance, else V is lowered until they just do.
  if (2.0 * speed_ * speed_ / acceleration > distance_) speed_ = std::sqrt(0.5 * acceleration * distance_);
  t_ramp_ = speed_ > 0 ? 2.0 * speed_ / acceleration : 0.0;
  duration_ = speed_ > 0 ? t_ramp_ + distance_ / speed_ : 0.0;
}

void SmoothProfile::Ramp(double t, double& s, double& sd, double& sdd) const {
  const double tau = t / t_ramp_, w = 2.0 * M_PI * tau;
  s = speed_ * t_ramp_ * (0.5 * tau * tau + (std::cos(w) - 1.0) / (4.0 * M_PI * M_PI));
  sd = speed_ * (tau - std::sin(w) / (2.0 * M_PI));
  sdd = speed_ / t_ramp_ * (1.0 - std::cos(w));
}

void SmoothProfile::Evaluate(double t, double& s, double& sd, double& sdd) const {
  s = sd = sdd = 0;
  if (duration_ <= 0) return;
  t = std::fmax(0.0, std::fmin(t, duration_));
  if (t < t_ramp_) {
    Ramp(t, s, sd, sdd);
  } else if (t <= duration_ - t_ramp_) {
    s = 0.5 * speed_ * t_ramp_ + speed_ * (t - t_ramp_);
    sd = speed_;
  } else {
    Ramp(duration_ - t, s, sd, sdd);
    s = distance_ - s;
    sdd = -sdd;
  }
  if (t >= duration_) s = distance_, sd = sdd = 0;
}

JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, double speed, double acceleration,
                              double dt) {
  CheckMotionParameters("joint move", speed, acceleration, dt);
  return PlanJointMove(q_start, q_goal, {Joints::Constant(speed), Joints::Constant(acceleration)}, dt);
}

JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, const JointMotionLimits& limits, double dt) {
  for (int i = 0; i < 6; ++i) CheckMotionParameters("joint move", limits.speed[i], limits.acceleration[i], dt);
  if (limits.speed.maxCoeff() > kUr5MaxJointSpeed + 1e-12) {
    throw std::invalid_argument("joint move: speed " + std::to_string(limits.speed.maxCoeff()) +
                                " rad/s exceeds the UR5 limit of pi");
  }
  if (!q_start.allFinite() || !q_goal.allFinite()) throw std::invalid_argument("joint move: non-finite joints");
  // Along the straight joint-space line q = q_start + s (q_goal - q_start), s in [0, 1], each joint
  // bounds the path speed and acceleration by its own limit over its travel.
  const Joints delta = q_goal - q_start;
  double speed = std::numeric_limits<double>::infinity(), acceleration = speed;
  for (int i = 0; i < 6; ++i) {
    if (delta[i] == 0) continue;
    speed = std::fmin(speed, limits.speed[i] / std::abs(delta[i]));
    acceleration = std::fmin(acceleration, limits.acceleration[i] / std::abs(delta[i]));
  }
  JointTrajectory trajectory;
  trajectory.dt = dt;
  if (!std::isfinite(speed)) {  // Already there.
    trajectory.q = {q_goal};
    trajectory.qd = trajectory.qdd = {Joints::Zero()};
    return trajectory;
  }
  const SmoothProfile profile(1.0, speed, acceleration);
  const int steps = static_cast<int>(std::ceil(profile.duration() / dt - 1e-9));
  for (int k = 0; k <= steps; ++k) {
    double s, sd, sdd;
    profile.Evaluate(k * dt, s, sd, sdd);
    trajectory.q.push_back(k == steps ? q_goal : Joints(q_start + s * delta));
    trajectory.qd.push_back(sd * delta);
    trajectory.qdd.push_back(sdd * delta);
  }
  trajectory.accel_s = trajectory.decel_s = profile.ramp_time();
  return trajectory;
}

namespace {

// `first` with `second` added from sample `start` on (second's motion relative to its first sample).
JointTrajectory Superpose(const JointTrajectory& first, const JointTrajectory& second, int start) {
  JointTrajectory sum = first;
  const Joints offset = first.q.back() - second.q.front();
  for (int k = 1; k < second.size(); ++k) {
    const int i = start + k;
    if (i < sum.size()) {
      sum.q[i] += second.q[k] - second.q.front();
      sum.qd[i] += second.qd[k];
      sum.qdd[i] += second.qdd[k];
    } else {
      sum.q.push_back(second.q[k] + offset);
      sum.qd.push_back(second.qd[k]);
      sum.qdd.push_back(second.qdd[k]);
    }
  }
  return sum;
}

// Whether the blended samples from `start` to `end` keep every joint within the limits, or within what
// one of the segments alone already asks there (a Cartesian line's own accelerations).
bool WithinLimits(const JointTrajectory& sum, const JointTrajectory& first, const JointTrajectory& second, int start,
                  const JointMotionLimits& limits, const SampleCheck& fits) {
  for (int i = start; i < first.size(); ++i) {
    const int k = i - start;
    for (int j = 0; j < 6; ++j) {
      const double speed = std::fmax(limits.speed[j], std::fmax(std::abs(first.qd[i][j]), std::abs(second.qd[k][j])));
      if (std::abs(sum.qd[i][j]) > speed * (1 + 1e-9)) return false;
      if (fits) continue;  // Accelerations are judged by their torques below.
      const double acceleration =
          std::fmax(limits.acceleration[j], std::fmax(std::abs(first.qdd[i][j]), std::abs(second.qdd[k][j])));
      if (std::abs(sum.qdd[i][j]) > acceleration * (1 + 1e-9)) return false;
    }
    if (fits && !fits(sum.q[i], sum.qd[i], sum.qdd[i])) return false;
  }
  return true;
}

}  // namespace

JointTrajectory BlendMoves(const JointTrajectory& first, const JointTrajectory& second, const JointMotionLimits& limits,
                           int* seam, const SampleCheck& fits) {
  if (first.q.empty() || second.q.empty()) {
    JointTrajectory t = first.q.empty() ? second : first;
    if (seam) *seam = first.q.empty() ? 0 : first.size() - 1;
    return t;
  }
  if (std::abs(first.dt - second.dt) > 1e-12) throw std::invalid_argument("BlendMoves: different dt");
  if ((second.q.front() - first.q.back()).cwiseAbs().maxCoeff() > 1e-6) {
    throw std::invalid_argument("BlendMoves: segments do not join");
  }
  // The second half of the slowing down at most: the corner cut stays within ~15 % of the ramps'
  // distance (a full overlap would start the second motion halfway through the first's ramp).
  int overlap = static_cast<int>(std::floor(0.5 * std::fmin(first.decel_s, second.accel_s) / first.dt + 1e-9));
  overlap = std::min({overlap, first.size() - 1, second.size() - 1});
  for (; overlap > 0; overlap /= 2) {
    const int start = first.size() - 1 - overlap;
    JointTrajectory sum = Superpose(first, second, start);
    if (!WithinLimits(sum, first, second, start, limits, fits)) continue;
    sum.accel_s = first.accel_s;
    sum.decel_s = second.decel_s;
    if (seam) *seam = start + overlap / 2;
    return sum;
  }
  JointTrajectory joined = first;
  joined.Append(second);
  joined.accel_s = first.accel_s;
  joined.decel_s = second.decel_s;
  if (seam) *seam = first.size() - 1;
  return joined;
}

CartesianPlan PlanCartesianLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed,
                                double acceleration, double dt, const SelectionOptions& selection) {
  CheckMotionParameters("Cartesian line", speed, acceleration, dt);
  CartesianPlan plan;
  const Eigen::Isometry3d X_BT_start = TcpPose(q_start);
  const Eigen::Vector3d p0 = X_BT_start.translation(), p1 = X_BT_goal.translation();
  const Eigen::Quaterniond r0(X_BT_start.linear()), r1(X_BT_goal.linear());
  const double length = std::fmax((p1 - p0).norm(), kMetresPerRadian * r0.angularDistance(r1));
  const SmoothProfile profile(length, speed, acceleration);
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
  trajectory.accel_s = trajectory.decel_s = profile.ramp_time();
  plan.status = CartesianPlanStatus::kOk;
  return plan;
}

}  // namespace sortcell::robot
