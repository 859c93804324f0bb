#include "robot/grasp_planner.h"

#include <algorithm>
#include <cmath>

#include "common/enum_names.h"
#include "robot/gripper_geometry.h"
#include "robot/joint_trajectory.h"
#include "robot/ur5_ik.h"

namespace sortcell::robot {

constexpr EnumNames<GraspStatus, 4> kGraspStatusNames{{{GraspStatus::kOk, "ok"},
                                                       {GraspStatus::kTooWide, "too_wide"},
                                                       {GraspStatus::kTooLow, "too_low"},
                                                       {GraspStatus::kUnreachable, "unreachable"}}};

const char* ToString(GraspStatus status) { return NameOf(kGraspStatusNames, status); }

std::vector<double> LiftClearancesHighestFirst(const GraspOptions& options) {
  std::vector<double> clearances;
  for (double clearance = options.lift_clearance; clearance >= options.min_lift_clearance - 1e-9; clearance -= 0.02) {
    clearances.push_back(clearance);
  }
  return clearances;
}

Eigen::Isometry3d TopDownTcpPose(const Eigen::Vector3d& p_W, double pinch_yaw) {
  // z_T down, y_T (the closing direction) along the pinch direction, x_T = y_T x z_T.
  const Eigen::Vector3d z(0, 0, -1), y(std::cos(pinch_yaw), std::sin(pinch_yaw), 0);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear().col(0) = y.cross(z);
  X.linear().col(1) = y;
  X.linear().col(2) = z;
  X.translation() = p_W;
  return X;
}

double GraspHeight(const ObjectFootprint& object, const GraspOptions& options) {
  const double height = object.top_z - object.base_z;
  const double lowest = kFingerTipBeyondTcp + options.table_clearance - object.base_z;
  const double over_neighbours = std::min(
      {options.min_tcp_z - object.base_z, height - options.min_pad_overlap, object.full_width_top_z - object.base_z});
  return std::max({0.5 * height, height - kPalmBeforeTcp + options.palm_clearance, over_neighbours, lowest});
}

GraspPlan PlanTopDownGrasp(const ObjectFootprint& object, const Joints& q_current, const GraspOptions& options) {
  GraspPlan plan;
  const double height = object.top_z - object.base_z;
  plan.open_gap = object.width + 2 * options.finger_clearance;
  if (plan.open_gap > kMaxGap) {
    plan.status = GraspStatus::kTooWide;
    return plan;
  }
  plan.grasp_height = GraspHeight(object, options);
  if (plan.grasp_height > height - 0.005) {
    plan.status = GraspStatus::kTooLow;
    return plan;
  }
  const double z_grasp = object.base_z + plan.grasp_height;
  const double z_pregrasp = std::fmax(object.top_z + kFingerTipBeyondTcp + options.approach_height, z_grasp + 0.05);
  const Eigen::Vector3d p(object.centre_xy.x(), object.centre_xy.y(), 0);

  // The highest reachable lift; of the two yaws, the one nearer to the current joints.
  double best_distance = 0;
  for (const double clearance : LiftClearancesHighestFirst(options)) {
    const double z_lift = std::fmax(object.base_z + clearance + plan.grasp_height, z_pregrasp);
    for (const double yaw : {object.pinch_yaw, object.pinch_yaw + M_PI}) {
      const Eigen::Isometry3d lift = TopDownTcpPose(p + Eigen::Vector3d(0, 0, z_lift), yaw);
      const Eigen::Isometry3d pregrasp = TopDownTcpPose(p + Eigen::Vector3d(0, 0, z_pregrasp), yaw);
      const Eigen::Isometry3d grasp = TopDownTcpPose(p + Eigen::Vector3d(0, 0, z_grasp), yaw);
      const auto q_lift = SelectNearest(SolveTcpIk(lift, q_current[5]), q_current, options.selection);
      if (!q_lift || std::abs(q_lift->q[2]) < options.min_elbow_bend) continue;
      const auto q_pre = SelectNearest(SolveTcpIk(pregrasp, q_lift->q[5]), q_lift->q, options.selection);
      if (!q_pre || std::abs(q_pre->q[2]) < options.min_elbow_bend) continue;
      if (!SelectNearest(SolveTcpIk(grasp, q_pre->q[5]), q_pre->q, options.selection)) continue;
      const double distance = (q_lift->q - q_current).norm();
      if (plan.status == GraspStatus::kOk && distance >= best_distance) continue;
      plan.status = GraspStatus::kOk;
      best_distance = distance;
      plan.X_WT_pregrasp = pregrasp;
      plan.X_WT_grasp = grasp;
      plan.X_WT_lift = lift;
      plan.q_lift = q_lift->q;
    }
    if (plan.status == GraspStatus::kOk) break;
  }
  return plan;
}

namespace {

struct TopDownCandidate {
  double distance;
  Eigen::Isometry3d X_WT;
  Joints q;
};

// Every reachable top-down pose at p_W (yaws yaw_offset + k yaw_step), nearest IK to q_current first.
std::vector<TopDownCandidate> TopDownPosesByDistance(const Eigen::Vector3d& p_W, const Joints& q_current,
                                                     const SelectionOptions& selection, double yaw_step,
                                                     double yaw_offset) {
  std::vector<TopDownCandidate> candidates;
  const int steps = std::max(1, static_cast<int>(std::lround(2 * M_PI / yaw_step)));
  for (int k = 0; k < steps; ++k) {
    const Eigen::Isometry3d X = TopDownTcpPose(p_W, yaw_offset + k * 2 * M_PI / steps);
    const auto chosen = SelectNearest(SolveTcpIk(X, q_current[5]), q_current, selection);
    if (chosen) candidates.push_back({(chosen->q - q_current).norm(), X, chosen->q});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const TopDownCandidate& a, const TopDownCandidate& b) { return a.distance < b.distance; });
  return candidates;
}

}  // namespace

PlacePlan PlanPlacement(const Eigen::Vector3d& p_W_floor, double grasp_height, const Joints& q_current,
                        const GraspOptions& options) {
  PlacePlan first;  // The nearest reachable placement, taken when no line down is smooth.
  for (const double clearance : LiftClearancesHighestFirst(options)) {
    const Eigen::Vector3d p_above = p_W_floor + Eigen::Vector3d(0, 0, clearance + grasp_height);
    for (const TopDownCandidate& c : TopDownPosesByDistance(p_above, q_current, options.selection,
                                                            options.place_yaw_step, options.place_yaw_offset)) {
      PlacePlan plan;
      plan.X_WT_above = plan.X_WT_release = c.X_WT;
      plan.q_above = c.q;
      plan.X_WT_release.translation().z() = p_W_floor.z() + options.release_clearance + grasp_height;
      if (!SelectNearest(SolveTcpIk(plan.X_WT_release, plan.q_above[5]), plan.q_above, options.selection)) continue;
      plan.ok = true;
      // Straight down from above the bin must not pass a branch change of the IK (a joint faster than
      // pi rad/s at any speed): with some yaws the line into a bin behind the robot does.
      if (PlanCartesianLine(plan.q_above, plan.X_WT_release, kMovelSpeed, kMovelAcceleration, 0.002, options.selection)
              .status == CartesianPlanStatus::kOk) {
        return plan;
      }
      if (!first.ok) first = plan;
    }
  }
  return first;
}

bool NearestTopDownPose(const Eigen::Vector3d& p_W, const Joints& q_current, const SelectionOptions& selection,
                        Eigen::Isometry3d& X_WT, Joints& q, double yaw_step, double yaw_offset) {
  const std::vector<TopDownCandidate> candidates =
      TopDownPosesByDistance(p_W, q_current, selection, yaw_step, yaw_offset);
  if (candidates.empty()) return false;
  X_WT = candidates.front().X_WT;
  q = candidates.front().q;
  return true;
}

}  // namespace sortcell::robot
