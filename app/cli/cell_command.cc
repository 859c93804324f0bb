#include "app/cli/cell_command.h"

#include <spdlog/fmt/fmt.h>

#include <fstream>
#include <iostream>
#include <memory>

#include "files/cell_file.h"
#include "files/data_dir.h"
#include "files/object_set.h"
#include "files/output_dir.h"
#include "simcell/sim_layout.h"
#include "sim/scene_composer.h"

namespace sortcell::app {
namespace {

struct CellCli {
  std::filesystem::path layout, objects, out;
};

std::string Describe(const files::CellFile& cell) {
  std::string text = fmt::format("Cell layout '{}' ({}): {} bins\n", cell.name, cell.source.string(), cell.bins.size());
  for (const auto& b : cell.bins) {
    text += fmt::format("  {:<12} at ({:.3f}, {:.3f}) m, {:.3f} x {:.3f} m inside\n", b.name, b.bin.p_W_floor.x(),
                        b.bin.p_W_floor.y(), 2 * b.bin.inner_half.x(), 2 * b.bin.inner_half.y());
  }
  text += "Rules:";
  for (const auto& [category, bin] : cell.rules.bin_of) text += fmt::format(" {} -> {};", category, bin);
  if (!cell.rules.otherwise.empty()) text += fmt::format(" anything else -> {};", cell.rules.otherwise);
  if (!cell.rules.reject_bin.empty()) {
    text += cell.rules.reject_below > 0
                ? fmt::format(" unsure (confidence below {}) -> {}", cell.rules.reject_below, cell.rules.reject_bin)
                : fmt::format(" unsure (with --reject-below) -> {}", cell.rules.reject_bin);
  }
  return text + "\n";
}

// Where each category of the set goes, and the warnings of bins too small for what they receive.
// Returns false if a category goes nowhere.
bool CheckSet(const files::CellFile& cell, const files::ObjectSet& set, std::string& text,
              std::vector<std::string>& warnings) {
  const cell::CellLayout layout = cell.Layout();
  std::vector<std::filesystem::path> fragments;
  std::vector<std::pair<std::string, std::string>> objects_and_bins;
  bool all_sorted = true;
  for (const auto& category : set.Categories()) {
    const auto bin = layout.rules.BinOf(category);
    text += fmt::format("  {:<12} -> {}\n", category, bin ? *bin : "NO BIN (no rule and no \"*\")");
    all_sorted = all_sorted && bin.has_value();
  }
  for (const auto& o : set.objects) {
    fragments.push_back(o.model);
    if (const auto bin = layout.rules.BinOf(o.category)) objects_and_bins.emplace_back(o.name, *bin);
  }
  const sim::Model model = sim::LoadComposedCell(std::filesystem::path(files::DataDir()) / "models", fragments,
                                                 set.source.string(), {}, files::BinsXml(cell));
  warnings = simcell::BinCapacityWarnings(model, layout, objects_and_bins);
  return all_sorted;
}

// bins.inc.xml and scene.xml (the cell with the layout's bins, no objects) into `out`.
void WriteScene(const files::CellFile& cell, const std::filesystem::path& out) {
  files::PrepareOutputDir(out);
  const std::filesystem::path models = std::filesystem::path(files::DataDir()) / "models";
  for (const auto& file : sim::ComposeCell(models, {}, {}, files::BinsXml(cell))) {
    const std::string name = file.name == "sortcell_composed.xml" ? "scene.xml" : file.name;
    std::ofstream(out / name) << file.text;
  }
}

}  // namespace

void AddCellCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  CLI::App* cell = app.add_subcommand("cell", "Work with cell layouts: bins and sorting rules (see `cell check`).");
  cell->require_subcommand(1);
  auto cli = std::make_shared<CellCli>();
  CLI::App* check = cell->add_subcommand(
      "check",
      "Reads a cell layout (scenes/cells/*.yaml) and refuses it with the reason if its bins overlap, stand off the "
      "table or in the pick area, or cannot be reached. With --objects: where each category goes, and a warning "
      "for each object a bin cannot hold lying flat. With --out: bins.inc.xml and scene.xml (mujoco-simulate). "
      "Exit 0 when every category has a bin and no bin is too small, 1 otherwise.");
  check->add_option("layout", cli->layout, "Cell layout YAML")->required();
  check->add_option("--objects", cli->objects, "Object set whose categories the rules must place");
  check->add_option("--out", cli->out, "Write bins.inc.xml and scene.xml here");
  check->callback([&run, cli, command_line] {
    run = [cli, command_line] {
      const files::CellFile file = files::ReadCellFile(cli->layout);
      std::cout << Describe(file);
      bool ok = true;
      if (!cli->objects.empty()) {
        const files::ObjectSet set = files::LoadObjectSet(cli->objects);
        std::string text = fmt::format("Object set '{}':\n", set.source.string());
        std::vector<std::string> warnings;
        ok = CheckSet(file, set, text, warnings);
        std::cout << text;
        for (const auto& w : warnings) std::cout << "warning: " << w << "\n";
        ok = ok && warnings.empty();
      }
      if (!cli->out.empty()) {
        WriteScene(file, cli->out);
        files::WriteJson(
            cli->out / "run.json",
            files::RunRecord(command_line, 0, {{"command", "cell check"}, {"layout", cli->layout.string()}}));
        std::cout << "Scene: mujoco-simulate " << (cli->out / "scene.xml").string() << "\n";
      }
      return ok ? 0 : 1;
    };
  });
}

}  // namespace sortcell::app
