#include "app/cli/episode_command.h"

#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>

#include "app/cli/cli_validators.h"
#include "files/data_dir.h"
#include "training/default_model.h"
#include "simcell/episode.h"
#include "files/object_set.h"

namespace sortcell::app {
namespace {

// "NAME=x,y", "NAME=x,y,yaw" or "NAME=x,y,yaw,lying".
simcell::ObjectPlacement ParsePlacement(const std::string& text) {
  const auto fail = [&] {
    return std::invalid_argument("--place: expected NAME=x,y[,yaw[,lying]] (metres, radians), got '" + text + "'");
  };
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw fail();
  simcell::ObjectPlacement p;
  p.name = text.substr(0, eq);
  std::vector<std::string> items;
  std::stringstream in(text.substr(eq + 1));
  std::string item;
  while (std::getline(in, item, ',')) items.push_back(item);
  if (items.size() == 4 && items[3] == "lying") {
    p.lying = true;
    items.pop_back();
  }
  if (items.size() < 2 || items.size() > 3) throw fail();
  std::vector<double> values;
  for (const std::string& number : items) {
    try {
      size_t used = 0;
      values.push_back(std::stod(number, &used));
      if (used != number.size()) throw fail();
    } catch (const std::logic_error&) {
      throw fail();
    }
  }
  p.x = values[0];
  p.y = values[1];
  p.yaw = values.size() == 3 ? values[2] : 0.0;
  return p;
}

struct EpisodeCli {
  simcell::EpisodeOptions options;
  std::vector<std::string> placements;
  std::string placement_mode = "sparse";
  std::string video_size = "1280x720";
  bool train_if_missing = false;
  std::string self_calibrate = "auto";
  double reject_below = 0;
  bool reject_below_given = false;
  std::vector<std::string> sets;  ///< Empty: ExpandEpisodeSets turned them into options before parsing.
};

// The keys --set accepts: every option's long names but set and help.
std::vector<std::string> SetKeys(const CLI::App& episode) {
  std::vector<std::string> keys;
  for (const CLI::Option* option : episode.get_options()) {
    for (const std::string& name : option->get_lnames()) {
      if (name != "set" && name != "help") keys.push_back(name);
    }
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

// "KEY=VALUE" -> "--KEY=VALUE".
std::string SetToOption(const std::string& text, const std::vector<std::string>& keys) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set: expected KEY=VALUE, found '" + text + "'");
  const std::string key = text.substr(0, eq);
  if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
    std::string valid;
    for (const auto& k : keys) valid += (valid.empty() ? "" : ", ") + k;
    throw std::invalid_argument("--set: unknown key '" + key + "' (valid keys: " + valid + ")");
  }
  return "--" + text;
}

// --placement and --lying-fraction: how the objects not placed by hand are drawn.
void AddPlacementOptions(CLI::App& cmd, EpisodeCli& cli) {
  cmd.add_option("--placement", cli.placement_mode,
                 "How the other objects are drawn: sparse (3 cm of table between them), dense (they may touch), "
                 "clustered (groups of 2-4 touching objects)")
      ->check(CLI::IsMember(AllNames(sim::kPlacementModeNames)))
      ->capture_default_str();
  cmd.add_option("--lying-fraction", cli.options.placement.lying_fraction,
                 "Chance (0-1) that a drawn object which can lie (bottles, boxes) is laid on its side at random yaw")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

}  // namespace

void AddSensorVariationOptions(CLI::App& cmd, simcell::EpisodeOptions& o) {
  cmd.add_option("--light-intensity", o.light_intensity, "Scale of the scene's lights")->capture_default_str();
  cmd.add_option("--noise-scale", o.noise_scale, "Scale of the Kinect's depth noise")->capture_default_str();
  cmd.add_option("--noise-seed", o.noise_seed,
                 "Another draw of the Kinect's noise over the same scene (0: the seed's own draw)")
      ->check(kUnsignedInteger)
      ->capture_default_str();
  cmd.add_option("--camera-shift", o.variation.camera_shift_m,
                 "Move the Kinect this far (m) in a random direction; the robot is given the nominal pose")
      ->capture_default_str();
  cmd.add_option("--camera-turn", o.variation.camera_turn_rad,
                 "Turn the Kinect by this angle (rad) about a random axis")
      ->capture_default_str();
}

void AddSetOption(CLI::App& cmd, std::vector<std::string>& sets) {
  cmd.add_option("--set", sets,
                 "Override an option (repeatable): KEY=VALUE is --KEY VALUE for any option above by its long name, "
                 "e.g. --set noise-scale=1.5 --set seed=3; applied after the other options, so it wins over the "
                 "option given directly")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  // One value per option, the last one given wins (so --set overrides).
  for (CLI::Option* option : cmd.get_options()) {
    if (option->get_items_expected_max() == 1) option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
}

std::vector<std::string> ExpandEpisodeSets(const CLI::App& episode, const std::vector<std::string>& args) {
  const std::vector<std::string> keys = SetKeys(episode);
  std::vector<std::string> kept, sets;
  bool options_ended = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") options_ended = true;
    if (!options_ended && arg == "--set" && i + 1 < args.size()) {
      sets.push_back(SetToOption(args[++i], keys));
    } else if (!options_ended && arg.rfind("--set=", 0) == 0) {
      sets.push_back(SetToOption(arg.substr(6), keys));
    } else {
      kept.push_back(arg);
    }
  }
  // Before a "--", so they are still options.
  const auto end = std::find(kept.begin(), kept.end(), "--");
  kept.insert(end, sets.begin(), sets.end());
  return kept;
}

namespace {

// --video, --stills and how the video is drawn.
void AddReviewOptions(CLI::App& cmd, EpisodeCli& cli) {
  simcell::EpisodeOptions& o = cli.options;
  cmd.add_option("--video", o.video, "Also write an H.264 MP4 from the review camera (30 fps, with overlay)");
  cmd.add_option(
      "--stills", o.stills,
      "Also write the Kinect still of every decision into this folder (still_<simulated ms>.png: the capture "
      "with each cluster outlined and named with its category and confidence)");
  cmd.add_option("--video-size", cli.video_size, "The video's WIDTHxHEIGHT (at most 1280x960)")
      ->check(kVideoSize)
      ->capture_default_str();
  cmd.add_flag("--video-shadows", o.video_options.shadows,
               "Draw the video with shadows and the floor's reflection (about 2.5x the rendering time)");
}

// The objects' friction, mass and colours varied.
void AddObjectVariationOptions(CLI::App& cmd, simcell::EpisodeOptions& o) {
  cmd.add_option("--friction-scale", o.variation.friction_scale, "Scale of the objects' friction")
      ->capture_default_str();
  cmd.add_option("--mass-scale", o.variation.mass_scale, "Scale of the objects' masses")->capture_default_str();
  cmd.add_option("--colour-jitter", o.variation.colour_jitter,
                 "Vary each object's colours at random (0-1): hue up to +-25 deg, saturation and brightness up to "
                 "+-30 %, times this")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

// How the cell runs: calibration, budgets, bins and rules, objects it does not know.
void AddCellOptions(CLI::App& cmd, EpisodeCli& cli) {
  simcell::EpisodeOptions& o = cli.options;
  cmd.add_option("--self-calibrate", cli.self_calibrate,
                 "Calibrate the camera's pose from the marker on the gripper before sorting: on, off, or auto (when "
                 "--camera-shift or --camera-turn displaces the camera)")
      ->check(CLI::IsMember(AllNames(simcell::kSelfCalibrationNames)))
      ->capture_default_str();
  cmd.add_option("--max-attempts", o.max_attempts_per_object, "Grasp attempts per object before giving it up")
      ->capture_default_str();
  cmd.add_option("--time-limit", o.time_limit_s, "Simulated seconds (0: 60 + 45 per object)")->capture_default_str();
  cmd.add_option("--cell", o.cell, "Cell layout: bins and rules (default: scenes/cells/default.yaml)");
  EpisodeCli* given = &cli;
  cmd.add_option("--reject-below", cli.reject_below,
                 "Objects recognised with a lower confidence (0-1) are unknown and go to the cell's reject bin "
                 "(default: the cell's reject_below)")
      ->check(CLI::Range(0.0, 1.0))
      ->each([given](const std::string&) { given->reject_below_given = true; });
  cmd.add_option("--unknown-set", o.unknown_set, "Object set the model was not trained on, for --unknown-objects");
  cmd.add_option("--unknown-objects", o.unknown_objects,
                 "Also place this many objects of --unknown-set: the rules send them to the reject bin")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
}

// Without --model: the set's cached default model, trained first with --train-if-missing.
void ResolveDefaultModel(simcell::EpisodeOptions& options, bool train_if_missing) {
  const files::ObjectSet set = files::LoadObjectSet(options.object_set);
  options.model = training::DefaultModelPath(set);
  if (train_if_missing) {
    training::EnsureDefaultModel(set);
  } else if (!std::filesystem::exists(options.model)) {
    throw std::invalid_argument("no trained model at " + options.model.string() + ": " +
                                training::DefaultModelHint(set));
  } else if (!training::DefaultModelIsCurrent(set)) {
    throw std::invalid_argument(
        "the cached model " + options.model.string() +
        " was trained on other object models or another Kinect colour model: " + training::DefaultModelHint(set));
  }
}

int RunEpisodeCommand(const EpisodeCli& cli, const std::vector<std::string>& command_line) {
  if (!cli.sets.empty()) throw std::logic_error("episode: --set reached the parser (ExpandEpisodeSets not applied)");
  simcell::EpisodeOptions options = cli.options;
  if (cli.reject_below_given) options.reject_below = cli.reject_below;
  for (const auto& p : cli.placements) options.placements.push_back(ParsePlacement(p));
  // Both checked by the parser.
  options.placement.mode = *sim::ParsePlacementMode(cli.placement_mode);
  options.self_calibrate = ParseName(simcell::kSelfCalibrationNames, cli.self_calibrate, "--self-calibrate");
  std::tie(options.video_options.width, options.video_options.height) = ParseVideoSize(cli.video_size);
  if (options.model.empty()) ResolveDefaultModel(options, cli.train_if_missing);
  const simcell::EpisodeMetrics metrics = simcell::RunEpisode(options, command_line);
  std::cout << simcell::EpisodeParagraph(metrics) << "\nMetrics: " << (options.out / "metrics.json").string();
  if (!options.video.empty()) std::cout << "\nVideo: " << options.video.string();
  std::cout << "\n";
  return 0;
}

}  // namespace

void AddEpisodeCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto cli = std::make_shared<EpisodeCli>();
  simcell::EpisodeOptions& o = cli->options;
  CLI::App* cmd = app.add_subcommand(
      "episode",
      "One sorting episode: K objects of the set placed at random on the table, then the cell looks, "
      "recognises, grasps and sorts them into their category's bins until none is left. Decisions come from "
      "the Kinect cloud and the joint encoders only; the simulator's ground truth scores the result. Writes "
      "metrics.json (per item and per episode) and run.json; prints a one-paragraph summary.");
  cmd->add_option("--scene", o.scene, "MJCF cell holding every object of the set, e.g. scenes/cell.xml")->required();
  o.object_set = std::filesystem::path(files::DataDir()) / "scenes" / "objects" / "paper.yaml";
  cmd->add_option("--object-set", o.object_set, "Object set YAML (names and categories)")->capture_default_str();
  cmd->add_option("--objects", o.objects, "How many objects to place (0: all of the set, at most 6)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed (uint64): placement, noise, lighting")
      ->check(kUnsignedInteger)
      ->capture_default_str();
  cmd->add_option("--model", o.model,
                  "Recognition model from sortcell train (default: <set>-color-cvfh-norm.model.json in the model "
                  "cache, build/models or $SORTCELL_MODEL_CACHE)");
  cmd->add_flag("--train-if-missing", cli->train_if_missing,
                "Without --model: train and cache the default model first if it is not there (sortcell train "
                "--objects; about 30 s for 150 scenes)");
  AddReviewOptions(*cmd, *cli);
  cmd->add_option("--out", o.out, "Output folder (created if missing)")->required();
  cmd->add_option("--place", cli->placements,
                  "Put an object at NAME=x,y[,yaw[,lying]] (world, m, rad; 'lying': on its side) instead of at random");
  AddPlacementOptions(*cmd, *cli);
  AddSensorVariationOptions(*cmd, o);
  AddObjectVariationOptions(*cmd, o);
  AddCellOptions(*cmd, *cli);
  AddSetOption(*cmd, cli->sets);
  cmd->callback(
      [&run, cli, command_line] { run = [cli, command_line] { return RunEpisodeCommand(*cli, command_line); }; });
}

}  // namespace sortcell::app
