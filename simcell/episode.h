#pragma once
/// @file
/// One sorting episode in the simulated cell: the harness around cell::SortingPolicy. It sets the
/// scene up (objects chosen and placed, variations applied, the nominal calibration given to the
/// robot), runs the policy over the simulated cell (sim_cell.h), and scores where every object ended
/// up from the simulator's ground truth (episode_scoring.h). The policy never sees that truth.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "simcell/episode_metrics.h"
#include "common/enum_names.h"
#include "robot/pick_selection.h"
#include "sim/clutter_placement.h"
#include "sim/scene_variation.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {

/// An object put at a chosen table position instead of a random one (scenarios, e.g. out of reach).
struct ObjectPlacement {
  std::string name;
  double x = 0, y = 0, yaw = 0;
  bool lying = false;  ///< Laid on its side (objects taller than they are narrow).
};

/// Whether an episode starts with the hand-eye self-calibration (simcell/calibration_run.h).
enum class SelfCalibration {
  kAuto,  ///< When the variation displaces the camera from the pose the robot was given.
  kOn,
  kOff,
};
/// Their spellings (`episode --self-calibrate`, the sweeps' self_calibrate axis).
inline constexpr EnumNames<SelfCalibration, 3> kSelfCalibrationNames{
    {{SelfCalibration::kAuto, "auto"}, {SelfCalibration::kOn, "on"}, {SelfCalibration::kOff, "off"}}};

struct EpisodeOptions {
  std::filesystem::path scene;       ///< MJCF cell holding every object of the set.
  std::filesystem::path cell;        ///< Bins and rules (scenes/cells/*.yaml); empty: the default cell.
  std::filesystem::path object_set;  ///< Which objects exist and their categories.
  /// Objects the model was not trained on, added to the scene: the rules send them to the reject bin.
  std::filesystem::path unknown_set;
  int unknown_objects = 0;          ///< How many of them (drawn at random).
  std::filesystem::path model;      ///< Trained recognition model (sortcell train).
  std::filesystem::path video;      ///< Empty: no video.
  sim::VideoOptions video_options;  ///< Its camera, size and frame rate.
  /// Empty: none. Else the Kinect still of every decision, as still_<simulated ms, 7 digits>.png: the
  /// capture's colour image with each cluster outlined and named with its category and confidence.
  std::filesystem::path stills;
  std::filesystem::path out;
  uint64_t seed = 0;
  int objects = 0;                          ///< How many of the set's objects to place (0: all of them, at most 6).
  std::vector<ObjectPlacement> placements;  ///< Placed first, as given; the rest at random.
  sim::PlacementOptions placement;          ///< How the rest are drawn: apart, touching, lying.
  // Variations (sweep axes).
  double light_intensity = 1.0;  ///< Scales the scene's lights (1 = as modelled).
  double noise_scale = 1.0;      ///< Scales the Kinect's depth noise (1 = the Kinect).
  uint64_t noise_seed = 0;       ///< Which draw of the Kinect's noise (KinectNoiseRng); the scene stays.
  sim::SceneVariation variation;
  SelfCalibration self_calibrate = SelfCalibration::kAuto;
  // The policy's budget.
  /// Grasp attempts at one position before it is given up.
  int max_attempts_per_object = robot::PickMemoryOptions{}.max_attempts_per_position;
  double time_limit_s = 0;  ///< Simulated seconds of sorting (0: 60 + 45 per object placed).
  /// Objects recognised less surely go to the cell's reject bin; unset: the cell file's reject_below.
  std::optional<double> reject_below;
};

/// Runs the episode and writes metrics.json and run.json (and the video) into options.out.
/// @throws std::invalid_argument naming the file or option for a bad scene, object set, model
///         (a category it does not know, a class without a bin), placement (an object placed twice,
///         objects that do not fit), count or output folder.
EpisodeMetrics RunEpisode(const EpisodeOptions& options, const std::vector<std::string>& command_line);

}  // namespace sortcell::simcell
