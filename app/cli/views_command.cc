#include "app/cli/views_command.h"

#include <fmt/core.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "assets/image_file.h"
#include "perception/pcd_io.h"
#include "training/dataset.h"
#include "training/view_sheet.h"

namespace sortcell::app {
namespace {

struct ViewsOptions {
  std::vector<std::string> rows;  // "DATASET:LABEL"
  int per_row = 8;
  int tile_px = 96;
  std::filesystem::path out;
};

// A row's title: what the views are and where they come from (a real capture, or the simulator through
// the Kinect as modelled or through a recipe's widened sensor).
std::string RowTitle(const training::Sample& first, const std::string& label, size_t views) {
  std::string kind = first.source == "rgbd-objects" ? "real Kinect" : "simulated, " + first.source;
  if (!first.fits_familiarity) kind += ", widened sensor";
  return fmt::format("{} ({}), {} views", label, kind, views);
}

training::ViewSheetRow LoadRow(const std::string& spec, std::map<std::filesystem::path, training::Dataset>& datasets,
                               int per_row) {
  const std::string where = "--row '" + spec + "'";
  const size_t colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) {
    throw std::invalid_argument(where + ": expected DATASET:LABEL (a dataset folder and a category or instance of it)");
  }
  const std::filesystem::path dir = spec.substr(0, colon);
  const std::string label = spec.substr(colon + 1);
  try {
    auto [it, fresh] = datasets.try_emplace(std::filesystem::weakly_canonical(dir));
    if (fresh) it->second = training::LoadDataset(dir);
    const training::Dataset& d = it->second;
    const std::vector<int> picked = training::SpreadSamples(d, label, per_row, where);
    training::ViewSheetRow row{RowTitle(d.samples[picked.front()], label, picked.size()), {}};
    for (int i : picked) row.views_C.push_back(perception::LoadCloud(dir / d.samples[i].cloud, false));
    return row;
  } catch (const std::invalid_argument& e) {  // Named by its row, as the row's own refusals are.
    const std::string what = e.what();
    throw std::invalid_argument(what.rfind(where, 0) == 0 ? what : where + ": " + what);
  }
}

int ViewsCommand(const ViewsOptions& o) {
  std::map<std::filesystem::path, training::Dataset> datasets;
  std::vector<training::ViewSheetRow> rows;
  for (const std::string& spec : o.rows) rows.push_back(LoadRow(spec, datasets, o.per_row));
  const cv::Mat sheet = training::DrawViewSheet(rows, o.tile_px);
  if (o.out.has_parent_path()) std::filesystem::create_directories(o.out.parent_path());
  if (!assets::WritePng(o.out, sheet)) throw std::runtime_error("cannot write '" + o.out.string() + "'");
  std::cout << "Wrote " << rows.size() << " rows of views to " << o.out.string() << "\n";
  return 0;
}

}  // namespace

void AddViewsCommand(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<ViewsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "views",
      "Draw a sheet of object views from datasets (sortcell dataset, --from-rgbd-objects or a model's "
      "MODEL.scenes/), one row per --row: the views of a category or instance spread evenly over the dataset, "
      "each drawn from its cloud as the camera saw it and fitted to its tile. E.g. the real views of an apple "
      "beside the simulated apples a model was trained on. Writes one PNG.");
  cmd->add_option("--row", o->rows, "DATASET:LABEL, a dataset folder and one of its categories or instances; repeat")
      ->required();
  cmd->add_option("--per-row", o->per_row, "Views per row")->check(CLI::Range(1, 40))->capture_default_str();
  cmd->add_option("--tile", o->tile_px, "Tile size in pixels")->check(CLI::Range(16, 512))->capture_default_str();
  cmd->add_option("--out", o->out, "PNG file to write")->required();
  cmd->callback([&run, o] { run = [o] { return ViewsCommand(*o); }; });
}

}  // namespace sortcell::app
