#include "simcell/sim_layout.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "files/data_dir.h"
#include "cell/layout_check.h"
#include "sim/camera_model.h"
#include "sim/ground_truth.h"
#include "sim/object_shape.h"
#include "sim/scene_composer.h"

namespace sortcell::simcell {
namespace {

constexpr double kSameBin = 1e-4;  // Bin positions and sizes that agree this well are the same (m).

}  // namespace

sim::Model LoadCellScene(const std::filesystem::path& scene, const files::CellFile& cell) {
  // MuJoCo finds virtual files by their bare name: this one stands for any include of "bins.inc.xml".
  std::vector<sim::Model::VirtualFile> files = sim::ModelTextures(std::filesystem::path(files::DataDir()) / "models");
  files.push_back({"bins.inc.xml", files::BinsXml(cell)});
  sim::Model model = sim::Model::FromFile(scene.string(), files);
  CheckSceneBins(model, cell);
  return model;
}

void CheckSceneBins(const sim::Model& model, const files::CellFile& cell) {
  sim::Data nominal(model);
  mj_forward(model.get(), nominal.get());
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("scene '" + model.source() + "': " + what + " (cell layout '" + cell.source.string() +
                                "'; a scene takes a layout's bins by including bins.inc.xml, as scenes/cell.xml does)");
  };
  std::set<std::string> in_scene;
  for (const auto& bin : sim::Bins(model)) {
    in_scene.insert(bin.name);
    const auto spec =
        std::find_if(cell.bins.begin(), cell.bins.end(), [&](const files::BinSpec& b) { return b.name == bin.name; });
    if (spec == cell.bins.end()) fail("bin '" + bin.name + "' is not in the layout");
    const Eigen::Vector3d p_W = sim::SitePose(nominal, bin.site).translation();
    if ((p_W - spec->bin.p_W_floor).norm() > kSameBin || (bin.inner_half - spec->bin.inner_half).norm() > kSameBin) {
      fail("bin '" + bin.name + "' stands elsewhere or has another size than in the layout");
    }
  }
  for (const auto& spec : cell.bins) {
    if (!in_scene.count(spec.name)) fail("no bin '" + spec.name + "'");
  }
}

cell::CellLayout ReadCellLayout(const sim::Model& model, const files::CellFile& cell) {
  CheckSceneBins(model, cell);
  cell::CellLayout layout = cell.Layout();
  sim::Data nominal(model);
  mj_forward(model.get(), nominal.get());
  const int table = mj_name2id(model.get(), mjOBJ_GEOM, "table_top");
  if (table < 0) throw std::invalid_argument("scene '" + model.source() + "': no table geom 'table_top'");
  // A plane geom's size holds its half extents (its collision is unbounded; this is the table drawn).
  const Eigen::Vector2d centre(nominal->geom_xpos[3 * table], nominal->geom_xpos[3 * table + 1]);
  const Eigen::Vector2d half(model.get()->geom_size[3 * table], model.get()->geom_size[3 * table + 1]);
  layout.table_min_xy = centre - half;
  layout.table_max_xy = centre + half;
  try {
    cell::CheckBinsOnTable(layout);  // The rest was checked when the cell file was read.
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("cell layout '" + cell.source.string() + "' in scene '" + model.source() +
                                "': " + e.what());
  }
  return layout;
}

std::vector<std::string> BinCapacityWarnings(const sim::Model& model, const cell::CellLayout& layout,
                                             const std::vector<std::pair<std::string, std::string>>& objects_and_bins) {
  std::vector<std::string> warnings;
  for (const auto& [object, bin_name] : objects_and_bins) {
    const sim::ObjectShape shape = sim::ObjectShapeOf(model, model.Id(mjOBJ_BODY, object));
    double longest = 2 * shape.upright.middle_radius;
    if (shape.lying) longest = std::max(longest, 2 * shape.lying->middle_radius);
    const double side = 2 * cell::BinNamed(layout, bin_name).inner_half.minCoeff();
    if (longest > side) {
      warnings.push_back(
          fmt::format("bin '{}' ({:.3f} m inside) cannot hold '{}' ({:.3f} m long) lying flat: it may "
                      "bounce out or rest on the rim; make the bin larger",
                      bin_name, side, object, longest));
    }
  }
  return warnings;
}

Eigen::Isometry3d NominalCameraPose(const sim::Model& model, const std::string& camera) {
  sim::Data nominal(model);
  mj_forward(model.get(), nominal.get());  // Camera poses come from mj_camlight, inside mj_forward.
  return sim::CameraPoseInWorld(model, nominal, model.Id(mjOBJ_CAMERA, camera));
}

}  // namespace sortcell::simcell
