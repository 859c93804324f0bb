#include "cell/carry_clearance.h"

#include <algorithm>

#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

double LeastClearanceOver(const robot::JointTrajectory& trajectory, const std::vector<HeldObject>& parts,
                          const CarryObstacles& obstacles, double beside,
                          const std::vector<Eigen::Vector2d>& plumb_xy) {
  double least = std::numeric_limits<double>::infinity();
  for (const robot::Joints& q : trajectory.q) {
    const Eigen::Isometry3d X_WT = robot::TcpPose(q);
    const Eigen::Vector2d p_xy = X_WT.translation().head<2>();
    const auto on = [&p_xy](const Eigen::Vector2d& p) { return (p_xy - p).norm() <= kOnPlumbLine; };
    if (std::any_of(plumb_xy.begin(), plumb_xy.end(), on)) continue;
    for (const HeldObject& part : parts) {
      const Eigen::Vector3d p_W_lowest = X_WT * Eigen::Vector3d(0, 0, part.below_tcp);  // Along z_T (down).
      const Eigen::Vector2d xy = p_W_lowest.head<2>();
      const double reach = part.radius + beside;
      for (const auto& disc : obstacles.discs) {
        if ((xy - disc.centre).norm() < disc.radius + reach) least = std::min(least, p_W_lowest.z() - disc.top_z);
      }
      for (const auto& box : obstacles.boxes) {
        const Eigen::Vector2d nearest = xy.cwiseMax(box.min_xy).cwiseMin(box.max_xy);
        if ((xy - nearest).norm() < reach) least = std::min(least, p_W_lowest.z() - box.top_z);
      }
    }
  }
  return least;
}

}  // namespace sortcell::cell
