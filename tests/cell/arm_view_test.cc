// The arm-in-view check from kinematics and calibration (unit): the observe pose and poses above
// the bins leave the workspace in view; the arm reaching into the workspace hides it.
#include "cell/arm_view.h"

#include <gtest/gtest.h>

#include "cell/cell_layout.h"
#include "robot/grasp_planner.h"

namespace sortcell::cell {
namespace {

// The cell's Kinect: (1.25, 0, 0.75), looking down 45 degrees at (0.5, 0, 0) (models/cell).
CameraCalibration CellCamera() {
  CameraCalibration camera;
  const Eigen::Vector3d p(1.25, 0, 0.75), z = (Eigen::Vector3d(0.5, 0, 0) - p).normalized();
  const Eigen::Vector3d x(0, 1, 0), y = z.cross(x);  // facing -x, the image right is +y
  camera.X_WC.linear().col(0) = x;
  camera.X_WC.linear().col(1) = y;
  camera.X_WC.linear().col(2) = z;
  camera.X_WC.translation() = p;
  return camera;
}

robot::Joints TopDownAt(const Eigen::Vector3d& p_W) {
  Eigen::Isometry3d X;
  robot::Joints q;
  EXPECT_TRUE(robot::NearestTopDownPose(p_W, CellLayout().q_observe, {}, X, q, M_PI / 2)) << p_W.transpose();
  return q;
}

TEST(WorkspaceView, ObservePoseAndBinsAreOutAndTheWorkspaceIsIn) {
  const CellLayout layout;
  const CameraCalibration camera = CellCamera();
  const WorkspaceView view(camera, layout.workspace_min_W, layout.workspace_max_W);
  auto in_view = [&](const robot::Joints& q, bool holding) {
    return view.ArmInView(q, holding ? std::optional<HeldObject>(HeldObject{0.11, 0.055}) : std::nullopt);
  };
  EXPECT_FALSE(in_view(layout.q_observe, false));
  for (const double y : {0.48, -0.48}) {  // Above the bins, holding an object.
    EXPECT_FALSE(in_view(TopDownAt({0.15, y, 0.45}), true)) << y;
    EXPECT_FALSE(in_view(TopDownAt({0.45, y, 0.35}), true)) << y;
  }
  EXPECT_TRUE(in_view(TopDownAt({0.5, 0.0, 0.4}), false));
  EXPECT_TRUE(in_view(TopDownAt({0.35, 0.2, 0.25}), true));
}

}  // namespace
}  // namespace sortcell::cell
