#include "app/episode_command.h"

#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli_validators.h"
#include "app/data_dir.h"
#include "app/default_model.h"
#include "app/episode.h"
#include "app/object_set.h"

namespace sortcell::app {
namespace {

// "NAME=x,y" or "NAME=x,y,yaw".
ObjectPlacement ParsePlacement(const std::string& text) {
  const auto fail = [&] {
    return std::invalid_argument("--place: expected NAME=x,y[,yaw] (metres, radians), got '" + text + "'");
  };
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw fail();
  ObjectPlacement p;
  p.name = text.substr(0, eq);
  std::vector<double> values;
  std::stringstream in(text.substr(eq + 1));
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size()) throw fail();
    } catch (const std::logic_error&) {
      throw fail();
    }
  }
  if (values.size() < 2 || values.size() > 3) throw fail();
  p.x = values[0];
  p.y = values[1];
  p.yaw = values.size() == 3 ? values[2] : 0.0;
  return p;
}

struct EpisodeCli {
  EpisodeOptions options;
  std::vector<std::string> placements;
  bool train_if_missing = false;
};

}  // namespace

void AddEpisodeCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto cli = std::make_shared<EpisodeCli>();
  EpisodeOptions& o = cli->options;
  CLI::App* cmd = app.add_subcommand(
      "episode",
      "One sorting episode: K objects of the set placed at random on the table, then the cell looks, "
      "recognises, grasps and sorts them into their category's bins until none is left. Decisions come from "
      "the Kinect cloud and the joint encoders only; the simulator's ground truth scores the result. Writes "
      "metrics.json (per item and per episode) and run.json; prints a one-paragraph summary.");
  cmd->add_option("--scene", o.scene, "MJCF cell holding every object of the set, e.g. scenes/cell.xml")->required();
  o.object_set = std::filesystem::path(DataDir()) / "scenes" / "objects" / "paper.yaml";
  cmd->add_option("--object-set", o.object_set, "Object set YAML (names and categories)")->capture_default_str();
  cmd->add_option("--objects", o.objects, "How many objects to place (0: all of the set, at most 6)")
      ->check(CLI::Range(0, 100))->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed (uint64): placement, noise, lighting")->check(kUnsignedInteger)->capture_default_str();
  cmd->add_option("--model", o.model,
                  "Recognition model from sortcell train (default: out/models/<set>-color-cvfh-norm.model.json)");
  cmd->add_flag("--train-if-missing", cli->train_if_missing,
                "Without --model: train and cache the default model first if it is not there (about 20 s)");
  cmd->add_option("--video", o.video, "Also write an H.264 MP4 from the review camera (30 fps, with overlay)");
  cmd->add_option("--out", o.out, "Output folder (created if missing)")->required();
  cmd->add_option("--place", cli->placements, "Put an object at NAME=x,y[,yaw] (world, m, rad) instead of at random");
  cmd->add_option("--light-intensity", o.light_intensity, "Scale of the scene's lights")->capture_default_str();
  cmd->add_option("--noise-scale", o.noise_scale, "Scale of the Kinect's depth noise")->capture_default_str();
  cmd->add_option("--friction-scale", o.variation.friction_scale, "Scale of the objects' friction")->capture_default_str();
  cmd->add_option("--mass-scale", o.variation.mass_scale, "Scale of the objects' masses")->capture_default_str();
  cmd->add_option("--camera-shift", o.variation.camera_shift_m,
                  "Move the Kinect this far (m) in a random direction; the robot keeps the nominal pose")
      ->capture_default_str();
  cmd->add_option("--camera-turn", o.variation.camera_turn_rad, "Turn the Kinect by this angle (rad) about a random axis")
      ->capture_default_str();
  cmd->add_option("--max-attempts", o.max_attempts_per_object, "Grasp attempts per object before giving it up")
      ->capture_default_str();
  cmd->add_option("--time-limit", o.time_limit_s, "Simulated seconds (0: 60 + 45 per object)")->capture_default_str();
  cmd->callback([&run, cli, command_line] {
    run = [cli, command_line] {
      EpisodeOptions options = cli->options;
      for (const auto& p : cli->placements) options.placements.push_back(ParsePlacement(p));
      if (options.model.empty()) {
        const ObjectSet set = LoadObjectSet(options.object_set);
        options.model = DefaultModelPath(set);
        if (cli->train_if_missing) {
          EnsureDefaultModel(set);
        } else if (!std::filesystem::exists(options.model)) {
          throw std::invalid_argument("no trained model at " + options.model.string() + ": " + DefaultModelHint(set));
        }
      }
      const nlohmann::json metrics = RunEpisode(options, command_line);
      std::cout << EpisodeParagraph(metrics) << "\nMetrics: " << (options.out / "metrics.json").string();
      if (!options.video.empty()) std::cout << "\nVideo: " << options.video.string();
      std::cout << "\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
