#include "app/episode/sim_layout.h"

#include <stdexcept>

#include "sim/camera_model.h"
#include "sim/ground_truth.h"

namespace sortcell::app {

cell::CellLayout ReadCellLayout(const sim::Model& model) {
  cell::CellLayout layout;
  // The nominal cell, before any variation: where the bins and the table were built.
  sim::Data nominal(model);
  mj_forward(model.get(), nominal.get());
  for (const auto& bin : sim::Bins(model)) layout.p_W_bin[bin.category] = sim::SitePose(nominal, bin.site).translation();
  const int table = mj_name2id(model.get(), mjOBJ_GEOM, "table_top");
  if (table < 0) throw std::invalid_argument("scene '" + model.source() + "': no table geom 'table_top'");
  // A plane geom's size holds its half extents (its collision is unbounded; this is the table drawn).
  const Eigen::Vector2d centre(nominal->geom_xpos[3 * table], nominal->geom_xpos[3 * table + 1]);
  const Eigen::Vector2d half(model.get()->geom_size[3 * table], model.get()->geom_size[3 * table + 1]);
  layout.table_min_xy = centre - half;
  layout.table_max_xy = centre + half;
  return layout;
}

Eigen::Isometry3d NominalCameraPose(const sim::Model& model, const std::string& camera) {
  sim::Data nominal(model);
  mj_forward(model.get(), nominal.get());  // Camera poses come from mj_camlight, inside mj_forward.
  return sim::CameraPoseInWorld(model, nominal, model.Id(mjOBJ_CAMERA, camera));
}

}  // namespace sortcell::app
