#pragma once
/// @file
/// Sweep specs (scenes/sweeps/*.yaml): many episodes of one cell, with scene variations drawn at
/// random or laid out as a grid.
///
///   scene: ../cell.xml                  # relative to the spec file
///   cell: ../cells/default.yaml         # optional: bins and rules (default: the default cell)
///   object_set: ../objects/paper.yaml
///   unknown_set: ../objects/ycb_dev.yaml  # objects the model does not know, for axis unknown_objects
///   model: ../../out/models/x.json      # optional; default: the cached default model of the set
///   seed: 0                             # base seed
///   episodes: 100                       # random: how many; grid: repeats per grid cell
///   seeds: [3, 7]                       # instead of episodes: explicit episode seeds
///   mode: random                        # random | grid
///   episode_timeout_s: 900              # wall clock, per episode (a hung worker is killed)
///   axes:                               # each a list of values, or a range {min: a, max: b}
///     objects: {min: 4, max: 6}         # integers
///     light_intensity: [0.8, 1.0, 1.2]
///     camera_shift_m, camera_turn_rad, noise_scale, friction_scale, mass_scale: numbers
///     model: [a.model.json, b.model.json]   # recognition models (descriptor axis)
///     placement: [sparse, dense, clustered] # how objects stand: apart, touching, in groups
///     lying_fraction: [0.3]             # chance a bottle or box lies on its side
///     colour_jitter: {min: 0, max: 1}  # each object's colours varied (hue, saturation, brightness)
///     self_calibrate: [on, off]         # hand-eye calibration first (default auto: when the camera moves)
///     unknown_objects: [0, 1, 2]        # objects of unknown_set added (the rules send them to the reject bin)
///     noise_seed: [1, 2]                # other draws of the Kinect's noise over the same scenes (integers >= 0)
///
/// In grid mode a range axis is drawn per repeat: every grid cell sees the same draws.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortcell::app {

/// One axis: a list of values (strings for `model`), or a uniform range.
struct SweepAxis {
  std::string name;
  std::vector<nlohmann::json> values;  ///< Empty for a range.
  double min = 0, max = 0;
  bool is_range() const { return values.empty(); }
};

struct SweepSpec {
  std::filesystem::path source;
  std::filesystem::path scene, object_set, model;  ///< Absolute; model empty: the default.
  std::filesystem::path cell;                      ///< Absolute; empty: the default cell.
  std::filesystem::path unknown_set;               ///< Absolute; empty: none (then no unknown_objects axis).
  uint64_t seed = 0;
  int episodes = 1;
  std::vector<uint64_t> seeds;  ///< When given, replaces `episodes`.
  bool grid = false;
  double episode_timeout_s = 900;
  std::vector<SweepAxis> axes;  ///< In the spec's order.

  /// Episodes in total: random: episodes (or seeds); grid: grid cells x repeats.
  int EpisodeCount() const;
  /// The episode's seed and axis values ({"objects": 5, "light_intensity": 0.93, ...}).
  /// Deterministic in (spec, index).
  std::pair<uint64_t, nlohmann::json> Episode(int index) const;
};

/// Names of the axes a spec may vary.
const std::vector<std::string>& SweepAxisNames();

/// Loads a spec; `overrides` ("KEY=VALUE", from `sortcell sweep --set`) replace keys of the file
/// before it is read: a top-level key (scene, cell, object_set, unknown_set, model, seed, episodes,
/// seeds, mode, episode_timeout_s) or an axis, "axes.NAME=VALUE" (one value: that axis fixed at it). VALUE is
/// YAML ("3", "[1, 2]", "{min: 1, max: 2}"); files given so are relative to the working folder;
/// setting one of episodes and seeds drops the other.
/// @throws std::invalid_argument "sweep spec '<file>': <what>" for a missing file, bad YAML, an
///         unknown key, a value of the wrong type, a range in grid mode or a missing scene, object set
///         or model file; "--set: ..." for an override that is not KEY=VALUE or names an unknown key.
SweepSpec LoadSweepSpec(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

}  // namespace sortcell::app
