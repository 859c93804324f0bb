#include "simcell/calibration_run.h"

#include <random>
#include <stdexcept>

#include "files/data_dir.h"
#include "files/output_dir.h"
#include "common/seeding.h"
#include "simcell/sim_layout.h"
#include "simcell/sim_rig.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::simcell {
namespace {

nlohmann::json Rows(const Eigen::Isometry3d& X) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({X(r, 0), X(r, 1), X(r, 2), X(r, 3)});
  return rows;
}

nlohmann::json ShowingJson(const cell::MarkerShowing& s) {
  nlohmann::json j = {{"reachable", s.reachable}, {"seen", s.seen.has_value()}};
  if (!s.reachable) return j;
  j["q"] = std::vector<double>(s.q.data(), s.q.data() + s.q.size());
  j["p_W_marker"] = {s.p_W_marker.x(), s.p_W_marker.y(), s.p_W_marker.z()};
  if (!s.seen) return j;
  j["p_C_marker"] = {s.seen->p_C_centre.x(), s.seen->p_C_centre.y(), s.seen->p_C_centre.z()};
  j["plane_points"] = s.seen->plane_points;
  j["plane_rms_m"] = s.seen->plane_rms_m;
  j["inlier"] = s.inlier;
  j["residual_m"] = s.residual_m;
  return j;
}

}  // namespace

bool SelfCalibrates(const EpisodeOptions& options) {
  switch (options.self_calibrate) {
    case SelfCalibration::kOn:
      return true;
    case SelfCalibration::kOff:
      return false;
    case SelfCalibration::kAuto:
      break;
  }
  return options.variation.camera_shift_m > 0 || options.variation.camera_turn_rad > 0;
}

CalibrationFigures ScoreCalibration(const cell::HandEyeCalibration& calibration, const Eigen::Isometry3d& X_WC_true) {
  CalibrationFigures f;
  f.status = cell::ToString(calibration.status);
  f.sightings = calibration.sightings;
  f.inliers = calibration.inliers;
  f.rms_residual_m = calibration.rms_residual_m;
  f.duration_s = calibration.end_s - calibration.start_s;
  f.error_m = robot::PositionError(calibration.X_WC, X_WC_true);
  f.error_rad = robot::RotationError(calibration.X_WC, X_WC_true);
  f.prior_error_m = robot::PositionError(calibration.X_WC_prior, X_WC_true);
  f.prior_error_rad = robot::RotationError(calibration.X_WC_prior, X_WC_true);
  return f;
}

nlohmann::json CalibrationJson(const cell::HandEyeCalibration& calibration, const CalibrationFigures& figures) {
  nlohmann::json showings = nlohmann::json::array();
  for (const auto& s : calibration.showings) showings.push_back(ShowingJson(s));
  return {{"status", figures.status},
          {"detail", calibration.detail},
          {"X_WC", Rows(calibration.X_WC)},
          {"X_WC_prior", Rows(calibration.X_WC_prior)},
          {"sightings", figures.sightings},
          {"inliers", figures.inliers},
          {"rms_residual_m", figures.rms_residual_m},
          {"max_residual_m", calibration.max_residual_m},
          {"duration_s", figures.duration_s},
          {"truth",
           {{"error_m", figures.error_m},
            {"error_rad", figures.error_rad},
            {"prior_error_m", figures.prior_error_m},
            {"prior_error_rad", figures.prior_error_rad}}},
          {"showings", showings}};
}

CalibrationFigures RunCalibration(const EpisodeOptions& options, const std::vector<std::string>& command_line) {
  CheckRigOptions(options);
  files::PrepareOutputDir(options.out);
  std::mt19937_64 rng = EpisodeRng(options.seed, 0);
  const files::CellFile cell = files::ReadCellFileOrDefault(options.cell);
  sim::Model model = LoadCellScene(options.scene, cell);
  const cell::CellLayout layout = ReadCellLayout(model, cell);
  const Eigen::Isometry3d X_WC_prior = NominalCameraPose(model, "kinect");
  SimRig rig(model, layout, options, rng);
  const cell::HandEyeCalibration calibration = cell::CalibrateHandEye(rig.cell(), layout, X_WC_prior);
  if (rig.video()) rig.video()->Close();
  const CalibrationFigures figures = ScoreCalibration(calibration, rig.TrueCameraPose());
  files::WriteJson(options.out / "calibration.json", CalibrationJson(calibration, figures));
  files::WriteJson(
      options.out / "run.json",
      files::RunRecord(command_line, options.seed, {{"command", "calibrate"}, {"scene", options.scene.string()}}));
  return figures;
}

}  // namespace sortcell::simcell
