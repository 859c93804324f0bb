#pragma once
/// @file
/// Hand-eye self-calibration in the simulated cell (cell/hand_eye_calibration.h): what `sortcell
/// calibrate` runs and what an episode starts with when it self-calibrates. The robot calibrates from
/// its encoders and the Kinect only; the scorer compares the result with the simulator's true camera
/// pose afterwards, to report the error.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "simcell/episode.h"
#include "simcell/episode_metrics.h"
#include "cell/hand_eye_calibration.h"

namespace sortcell::simcell {

/// Whether an episode self-calibrates: as options.self_calibrate says, or (auto) when its variation
/// displaces the camera from the pose the robot was given.
bool SelfCalibrates(const EpisodeOptions& options);

/// The calibration's figures, with its error and the prior's against the true pose X_WC_true.
CalibrationFigures ScoreCalibration(const cell::HandEyeCalibration& calibration, const Eigen::Isometry3d& X_WC_true);

/// calibration.json: the status, the calibrated and prior X_WC (4x4 rows), the fit's figures, every
/// place the marker was shown at, and (scoring) the errors against the true pose.
nlohmann::json CalibrationJson(const cell::HandEyeCalibration& calibration, const CalibrationFigures& figures);

/// `sortcell calibrate`: the cell as the options vary it (scene, seed, lighting, noise, camera
/// displacement, video), calibrated; writes calibration.json and run.json into options.out.
/// @throws std::invalid_argument naming the file or option for a bad scene or output folder.
CalibrationFigures RunCalibration(const EpisodeOptions& options, const std::vector<std::string>& command_line);

}  // namespace sortcell::simcell
