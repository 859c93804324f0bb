#include "cell/layout_check.h"

#include <stdexcept>

#include <fmt/format.h>

#include "cell/bin_fill.h"
#include "robot/grasp_planner.h"

namespace sortcell::cell {
namespace {

constexpr double kBinGap = 0.01;          // Between two bins' outer walls (m).
constexpr double kHeldAboveGrasp = 0.05;  // A held object's bottom below the TCP, for the reach check (m).

// The bin's outer extent seen from above (world xy, m).
struct Footprint {
  Eigen::Vector2d min, max;
};

Footprint OuterOf(const CellLayout& layout, const Bin& bin) {
  const Eigen::Vector2d half = bin.inner_half.array() + layout.bin_wall_thickness;
  return {bin.p_W_floor.head<2>() - half, bin.p_W_floor.head<2>() + half};
}

bool Overlap(const Footprint& a, const Footprint& b, double gap) {
  return (a.min.array() < b.max.array() + gap).all() && (b.min.array() < a.max.array() + gap).all();
}

std::string Xy(const Eigen::Vector3d& p) { return fmt::format("({:.3f}, {:.3f})", p.x(), p.y()); }

void CheckOne(const CellLayout& layout, const std::string& name, const Bin& bin) {
  const Eigen::Vector2d inside = 2 * bin.inner_half;
  if (!(inside.minCoeff() >= kMinBinInside && inside.maxCoeff() <= kMaxBinInside)) {
    throw std::invalid_argument(fmt::format("bin '{}': {:.3f} x {:.3f} m inside (expected {}-{} m a side)", name,
                                            inside.x(), inside.y(), kMinBinInside, kMaxBinInside));
  }
  const Footprint outer = OuterOf(layout, bin);
  const Footprint pick_area{layout.workspace_min_W.head<2>(), layout.workspace_max_W.head<2>()};
  if (Overlap(outer, pick_area, 0)) {
    throw std::invalid_argument(
        fmt::format("bin '{}' at {} reaches into the pick area the camera watches (x {}..{}, y {}..{} m)", name,
                    Xy(bin.p_W_floor), pick_area.min.x(), pick_area.max.x(), pick_area.min.y(), pick_area.max.y()));
  }
  // The arm must place into every slot as it will in an episode (robot::PlanPlacement from home).
  std::vector<Eigen::Vector3d> releases{bin.p_W_floor};
  for (size_t k = 0; k < layout.bin_slots.size(); ++k) releases.push_back(BinSlot(layout, name, static_cast<int>(k)));
  robot::GraspOptions options;
  options.place_yaw_step = layout.place_yaw_step;
  for (const auto& p_W : releases) {
    if (!robot::PlanPlacement(p_W, kHeldAboveGrasp, layout.q_observe, options).ok) {
      throw std::invalid_argument(
          fmt::format("bin '{}' at {}: the arm cannot reach down into it at {}", name, Xy(bin.p_W_floor), Xy(p_W)));
    }
  }
  // A lying object, along a diagonal, let go above the walls (BinFill::Lying of the empty bin).
  const BinRelease lying = BinFill(layout).Lying(name);
  options.place_yaw_step = lying.yaw_step;
  options.place_yaw_offset = lying.yaw_offset;
  options.release_clearance = lying.clearance;
  if (!robot::PlanPlacement(lying.p_W_floor, kHeldAboveGrasp, layout.q_observe, options).ok) {
    throw std::invalid_argument(
        fmt::format("bin '{}' at {}: the arm cannot lay a lying object along its diagonal", name, Xy(bin.p_W_floor)));
  }
}

}  // namespace

void CheckBinsOnTable(const CellLayout& layout) {
  for (const auto& [name, bin] : layout.bins) {
    const Footprint outer = OuterOf(layout, bin);
    if ((outer.min.array() < layout.table_min_xy.array()).any() ||
        (outer.max.array() > layout.table_max_xy.array()).any()) {
      throw std::invalid_argument(fmt::format("bin '{}' at {} stands off the table (x {}..{}, y {}..{} m)", name,
                                              Xy(bin.p_W_floor), layout.table_min_xy.x(), layout.table_max_xy.x(),
                                              layout.table_min_xy.y(), layout.table_max_xy.y()));
    }
  }
}

void CheckBins(const CellLayout& layout) {
  if (layout.bins.empty()) throw std::invalid_argument("no bins");
  CheckBinsOnTable(layout);
  for (const auto& [name, bin] : layout.bins) CheckOne(layout, name, bin);
  for (auto a = layout.bins.begin(); a != layout.bins.end(); ++a) {
    for (auto b = std::next(a); b != layout.bins.end(); ++b) {
      if (Overlap(OuterOf(layout, a->second), OuterOf(layout, b->second), kBinGap)) {
        throw std::invalid_argument(
            fmt::format("bins '{}' and '{}' overlap (their walls must stay {} m apart)", a->first, b->first, kBinGap));
      }
    }
  }
}

void CheckRules(const CellLayout& layout, const std::vector<std::string>& classes) {
  const SortingRules& rules = layout.rules;
  for (const auto& bin : rules.NamedBins()) {
    if (!layout.bins.count(bin)) throw std::invalid_argument("rules: no bin '" + bin + "' in the layout");
  }
  if (!(rules.reject_below >= 0 && rules.reject_below <= 1)) {
    throw std::invalid_argument(fmt::format("rules: reject_below must be in [0, 1], got {}", rules.reject_below));
  }
  if (rules.reject_below > 0 && rules.reject_bin.empty()) {
    throw std::invalid_argument("rules: reject_below needs a reject bin");
  }
  for (const auto& c : classes) {
    if (!rules.BinOf(c)) {
      throw std::invalid_argument("rules: the model's class '" + c + "' goes to no bin (no rule for it and no \"*\")");
    }
  }
}

}  // namespace sortcell::cell
