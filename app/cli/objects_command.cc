#include "app/cli/objects_command.h"

#include <spdlog/fmt/fmt.h>

#include <iostream>
#include <memory>

#include "files/object_set.h"
#include "files/output_dir.h"
#include "app/objects/object_check.h"
#include "robot/gripper_geometry.h"

namespace sortcell::app {
namespace {

struct ObjectsCli {
  std::filesystem::path set;
  std::filesystem::path out;
  ObjectCheckOptions options;
};

std::string Row(const ObjectCheckResult& r) {
  const std::string pieces = r.import ? std::to_string(r.import->collision_pieces) : "-";
  const std::string mass = r.import ? fmt::format("{:.3f}", r.import->mass) : "-";
  const std::string lying = r.grip_width_lying ? fmt::format("{:.1f}", 1000 * *r.grip_width_lying) : "-";
  std::string notes = r.why_not;
  if (r.grip_width_lying && *r.grip_width_lying >= robot::kMaxGap) {
    notes += std::string(notes.empty() ? "" : "; ") + "ungraspable when lying";
  }
  return fmt::format("{:<18} {:<9} {:>6} {:>7} {:>6.1f} {:>6} {:>7.1f} {:>7.1f} {:<6} {:<10} {}", r.name, r.category,
                     pieces, mass, 1000 * r.grip_width, lying, 1000 * r.bounce, r.tilt_deg, r.rests ? "yes" : "NO",
                     r.graspable ? "yes" : "NO (wide)", notes);
}

std::string Summary(const ObjectCheck& check, const std::filesystem::path& out) {
  std::string text =
      fmt::format("{:<18} {:<9} {:>6} {:>7} {:>6} {:>6} {:>7} {:>7} {:<6} {:<10} {}\n", "object", "category", "pieces",
                  "kg", "grip", "lying", "bounce", "tilt", "rests", "graspable", "notes");
  text += fmt::format("{:<18} {:<9} {:>6} {:>7} {:>6} {:>6} {:>7} {:>7}\n", "", "", "", "", "mm", "mm", "mm", "deg");
  int resting = 0, graspable = 0;
  for (const auto& r : check.objects) {
    text += Row(r) + "\n";
    resting += r.rests;
    graspable += r.graspable;
  }
  text += fmt::format("{} of {} objects rest, {} can be grasped. Results: {}; stills: {}; scene: mujoco-simulate {}",
                      resting, check.objects.size(), graspable, (out / "check.json").string(),
                      check.stills.empty() ? "" : check.stills.front().string(), check.scene.string());
  return text;
}

}  // namespace

void AddObjectsCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  CLI::App* objects = app.add_subcommand("objects", "Work with object sets (see `objects check`).");
  objects->require_subcommand(1);
  auto cli = std::make_shared<ObjectsCli>();
  CLI::App* check = objects->add_subcommand(
      "check",
      "Imports every object of a set (URDF and mesh objects: into the import cache) and drops each on the cell's "
      "table: its settled pose, whether it rests (no bounce, jitter or creep), its size against the gripper's "
      "stroke. Writes check.json, a still per batch of objects (objects_<k>.png), scene.xml (open it with "
      "mujoco-simulate) and run.json. Exit 0 when every object rests and can be grasped, 1 otherwise.");
  check->add_option("set", cli->set, "Object set YAML")->required()->check(CLI::ExistingFile);
  check->add_option("--out", cli->out, "Output folder (created if missing)")->required();
  check->add_option("--settle", cli->options.settle_s, "Seconds each object is watched after its release")
      ->check(CLI::Range(1.0, 60.0))
      ->capture_default_str();
  check->add_option("--drop-height", cli->options.drop_height, "Released this far above its resting height (m)")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  check->callback([&run, cli, command_line] {
    run = [cli, command_line] {
      const files::ObjectSet set = files::LoadObjectSet(cli->set);
      const ObjectCheck result = CheckObjects(set, cli->out, cli->options);
      files::WriteJson(
          cli->out / "run.json",
          files::RunRecord(command_line, 0, {{"command", "objects check"}, {"object_set", cli->set.string()}}));
      std::cout << Summary(result, cli->out) << "\n";
      for (const auto& r : result.objects) {
        if (!r.rests || !r.graspable) return 1;
      }
      return 0;
    };
  });
}

}  // namespace sortcell::app
