#include "cell/cell_layout.h"

#include <cmath>
#include <stdexcept>

namespace sortcell::cell {

std::vector<Eigen::Vector2d> BinWallOutlines(const CellLayout& layout, double spacing) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& [category, p_W_bin] : layout.p_W_bin) {
    for (const double half : {layout.bin_inner_half_width, layout.bin_outer_half_width}) {
      const int n = static_cast<int>(std::ceil(2 * half / spacing));
      for (int i = 0; i <= n; ++i) {
        const double t = -half + 2 * half * i / n;
        for (const Eigen::Vector2d& p : {Eigen::Vector2d(t, -half), Eigen::Vector2d(t, half), Eigen::Vector2d(-half, t),
                                         Eigen::Vector2d(half, t)}) {
          points.push_back(p_W_bin.head<2>() + p);
        }
      }
    }
  }
  return points;
}

Eigen::Vector3d BinSlot(const CellLayout& layout, const std::string& category, int filled) {
  const auto bin = layout.p_W_bin.find(category);
  if (bin == layout.p_W_bin.end()) throw std::invalid_argument("cell layout: no bin for category '" + category + "'");
  if (layout.bin_slots.empty()) return bin->second;
  return bin->second + layout.bin_slots[filled % layout.bin_slots.size()];
}

}  // namespace sortcell::cell
