#pragma once
/// @file
/// One sorting episode (paper section 2.3): the cell looks at the table, recognises each object,
/// grasps it where its cloud says it stands and drops it into its category's bin, until no object is
/// left. The loop decides from the Kinect's cloud and the arm's encoders and gripper sensors only;
/// the simulator's ground truth sets the scene up and scores the result afterwards (episode_scoring.h).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/scene_variation.h"

namespace sortcell::app {

/// An object put at a chosen table position instead of a random one (scenarios, e.g. out of reach).
struct ObjectPlacement {
  std::string name;
  double x = 0, y = 0, yaw = 0;
};

struct EpisodeOptions {
  std::filesystem::path scene;       ///< MJCF cell holding every object of the set.
  std::filesystem::path object_set;  ///< Which objects exist and their categories.
  std::filesystem::path model;       ///< Trained recognition model (sortcell train).
  std::filesystem::path video;       ///< Empty: no video.
  std::filesystem::path out;
  uint64_t seed = 0;
  int objects = 0;  ///< How many of the set's objects to place (0: all of them, at most 6).
  std::vector<ObjectPlacement> placements;  ///< Placed first, as given; the rest at random.
  // Variations (sweep axes).
  double light_intensity = 1.0;  ///< Scales the scene's lights (1 = as modelled).
  double noise_scale = 1.0;      ///< Scales the Kinect's depth noise (1 = the Kinect).
  sim::SceneVariation variation;
  // Limits.
  int max_attempts_per_object = 3;  ///< Grasp attempts at one position before it is given up.
  double time_limit_s = 0;          ///< Simulated seconds (0: 60 + 45 per object).
};

/// Runs the episode and writes metrics.json and run.json (and the video) into options.out.
/// Returns the metrics (see README: {"seed", "items": [...], "summary": {...}}).
/// @throws std::invalid_argument naming the file or option for a bad scene, object set, model,
///         placement, count or output folder.
nlohmann::json RunEpisode(const EpisodeOptions& options, const std::vector<std::string>& command_line);

/// The one-paragraph summary printed after an episode.
std::string EpisodeParagraph(const nlohmann::json& metrics);

}  // namespace sortcell::app
