// Hand-eye self-calibration in the simulated cell: the gripper's marker is found where the simulator
// has it, and a calibration recovers a displaced camera's pose.
#include "simcell/calibration_run.h"

#include <gtest/gtest.h>

#include "files/data_dir.h"
#include "simcell/sim_cell.h"
#include "simcell/sim_layout.h"
#include "cell/hand_eye_calibration.h"
#include "perception/cloud_pinhole.h"
#include "perception/marker_sighting.h"
#include "robot/gripper_geometry.h"
#include "robot/ur5_kinematics.h"
#include "sim/ground_truth.h"
#include "sim/kinect_camera.h"
#include "sim/kinect_noise.h"
#include "sim/object_placement.h"
#include "sim/point_cloud.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

std::filesystem::path CellScene() { return std::filesystem::path(SORTCELL_SOURCE_DIR) / "scenes" / "cell.xml"; }

// At every place the calibration shows the marker: the sighting's centre against the marker site's
// true position in the true camera frame, clean and through the Kinect's noise.
TEST(MarkerSighting, FindsTheGrippersMarkerWhereTheSimulatorHasIt) {
  sim::Model model = files::LoadScene(CellScene());
  const cell::CellLayout layout = simcell::ReadCellLayout(model, files::ReadCellFile(files::DefaultCellFile()));
  sim::Data data(model);
  const std::vector<std::string> bodies = sim::FreeBodyNames(model);  // Off the table: the arm sweeps it.
  for (size_t i = 0; i < bodies.size(); ++i)
    sim::StowObject(model, data, model.Id(mjOBJ_BODY, bodies[i]), static_cast<int>(i));
  sim::KinectCamera kinect(model, "kinect");
  sim::KinectNoiseParams noise;
  std::mt19937_64 rng(1);
  const int site = model.Id(mjOBJ_SITE, "calibration_marker");
  const auto joints = cell::MarkerShowingJoints(simcell::NominalCameraPose(model, "kinect"), layout.q_observe, {});
  for (const bool noisy : {false, true}) {
    double worst = 0;
    int found = 0;
    for (const auto& q : joints) {
      ASSERT_TRUE(q.has_value());
      for (int i = 0; i < 6; ++i) data->qpos[i] = (*q)(i);
      mj_forward(model.get(), data.get());
      sim::FrameTruth truth;
      const auto cloud = sim::ToOrganizedCloud(kinect.Capture(data, noisy ? &noise : nullptr, &rng, &truth));
      const Eigen::Vector3d p_C_true = truth.X_WC.inverse() * sim::SitePose(data, site).translation();
      const auto seen = perception::FindMarker(*cloud, perception::FitPinhole(*cloud), robot::kMarkerId);
      if (!seen) continue;
      ++found;
      const double error = (seen->p_C_centre - p_C_true).norm();
      worst = std::max(worst, error);
    }
    // A marker far up in the view, 4 px a cell, may not decode; the fit does without it.
    EXPECT_GE(found, static_cast<int>(joints.size()) - 2) << (noisy ? "through the Kinect's noise" : "clean");
    EXPECT_LT(worst, noisy ? 0.001 : 0.0005) << (noisy ? "through the Kinect's noise" : "clean");
  }
}

// The goal: a camera displaced by 5 cm and turned by 0.05 rad is calibrated to within 2 mm and
// 0.002 rad in at most 20 simulated seconds, through the Kinect's noise.
TEST(HandEyeCalibration, RecoversADisplacedCamerasPose) {
  const sortcell_test::TempDir dir;
  simcell::EpisodeOptions options;
  options.scene = CellScene();
  options.seed = 3;
  options.variation.camera_shift_m = 0.05;
  options.variation.camera_turn_rad = 0.05;
  options.out = dir.path() / "calibration";
  const simcell::CalibrationFigures figures = simcell::RunCalibration(options, {"test"});
  EXPECT_EQ(figures.status, "ok");
  EXPECT_NEAR(figures.prior_error_m, 0.05, 1e-6);
  EXPECT_LE(figures.error_m, 0.002);
  EXPECT_LE(figures.error_rad, 0.002);
  EXPECT_LE(figures.duration_s, 20.0);
  EXPECT_GE(figures.inliers, 12);
  EXPECT_TRUE(std::filesystem::exists(options.out / "calibration.json"));
}

}  // namespace
}  // namespace sortcell::app
