#include "cell/arm_view.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "robot/gripper_geometry.h"

namespace sortcell::cell {
namespace {

constexpr double kMargin = 0.02;  // Added to every capsule's radius (m).
// Workspace surface samples this far apart (m): closer than the thinnest capsule's radius, so no
// capsule's shadow slips between them.
constexpr double kSurfaceSpacing = 0.03;

// Points on the surface of the box [lo, hi], at most `spacing` apart. A sphere that hides any point of
// the box hides one of its surface (the one where the ray enters it, or leaves it behind the sphere).
std::vector<Eigen::Vector3d> BoxSurface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing) {
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3i n;
  for (int i = 0; i < 3; ++i) n[i] = 1 + static_cast<int>(std::ceil((hi[i] - lo[i]) / spacing));
  for (int i = 0; i <= n.x(); ++i) {
    for (int j = 0; j <= n.y(); ++j) {
      for (int k = 0; k <= n.z(); ++k) {
        if (i != 0 && i != n.x() && j != 0 && j != n.y() && k != 0 && k != n.z()) continue;  // Inside.
        const Eigen::Vector3d f(double(i) / n.x(), double(j) / n.y(), double(k) / n.z());
        points.push_back(lo + (hi - lo).cwiseProduct(f));
      }
    }
  }
  return points;
}

}  // namespace

// The arm's capsules at q (world frame): the URDF's collision envelope (models/ur5/ur5.urdf, in the
// generated ur5_urdf.h), then the gripper around the flange's axis down to its finger tips.
CapsuleList ArmCapsules(const robot::Joints& q, const std::optional<HeldObject>& held) {
  const robot::LinkFrames X = robot::ForwardKinematicsAll(q);
  auto at = [&](int frame, double x, double y, double z) {
    return Eigen::Vector3d(X[frame] * Eigen::Vector3d(x, y, z));
  };
  CapsuleList capsules;
  for (const auto& c : robot::ur5_urdf::kCollisionCapsules) {
    capsules.push_back({at(c.frame, c.a[0], c.a[1], c.a[2]), at(c.frame, c.b[0], c.b[1], c.b[2]), c.radius});
  }
  capsules.push_back(
      {at(6, 0, 0, 0), at(6, 0, 0, robot::kTcpOffsetZ + robot::kFingerTipBeyondTcp), robot::kGripperEnvelopeRadius});
  if (held) {
    capsules.push_back(
        {at(6, 0, 0, robot::kTcpOffsetZ), at(6, 0, 0, robot::kTcpOffsetZ + held->below_tcp), held->radius});
  }
  for (auto& c : capsules) c.radius += kMargin;
  return capsules;
}

WorkspaceView::WorkspaceView(const CameraCalibration& camera, const Eigen::Vector3d& workspace_min_W,
                             const Eigen::Vector3d& workspace_max_W)
    : p_WC_(camera.X_WC.translation()) {
  for (const Eigen::Vector3d& b : BoxSurface(workspace_min_W, workspace_max_W, kSurfaceSpacing)) {
    surface_from_camera_W_.push_back(b - p_WC_);
    surface_range_.push_back(surface_from_camera_W_.back().norm());
  }
}

bool WorkspaceView::ArmInView(const robot::Joints& q, const std::optional<HeldObject>& held) const {
  const Eigen::Vector3d& o = p_WC_;
  for (const Capsule& capsule : ArmCapsules(q, held)) {
    // Spheres along the capsule, at most half a radius apart. A sphere at distance D with radius r
    // hides the cone of rays within asin(r / D) of its centre's, beyond D - r.
    const int n = 1 + static_cast<int>((capsule.b - capsule.a).norm() / (0.5 * capsule.radius));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector3d p = capsule.a + (capsule.b - capsule.a) * (double(i) / n);
      const double distance = (p - o).norm();
      if (distance <= capsule.radius) return true;  // At the lens: it hides everything.
      const Eigen::Vector3d axis = (p - o) / distance;
      const double cos_cone = std::sqrt(1.0 - std::pow(capsule.radius / distance, 2));
      for (size_t k = 0; k < surface_range_.size(); ++k) {
        const double range = surface_range_[k];
        if (range > distance - capsule.radius && axis.dot(surface_from_camera_W_[k]) >= cos_cone * range) return true;
      }
    }
  }
  return false;
}

}  // namespace sortcell::cell
