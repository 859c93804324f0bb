#include "cell/cell_layout.h"

#include <cmath>
#include <stdexcept>

namespace sortcell::cell {

std::vector<Eigen::Vector2d> BinWallOutlines(const CellLayout& layout, double spacing) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& [name, bin] : layout.bins) {
    for (const Eigen::Vector2d& half :
         {bin.inner_half, Eigen::Vector2d(bin.inner_half.array() + layout.bin_wall_thickness)}) {
      for (int axis = 0; axis < 2; ++axis) {
        const int n = static_cast<int>(std::ceil(2 * half[axis] / spacing));
        for (int i = 0; i <= n; ++i) {
          for (const double side : {-1.0, 1.0}) {
            Eigen::Vector2d p;
            p[axis] = -half[axis] + 2 * half[axis] * i / n;
            p[1 - axis] = side * half[1 - axis];
            points.push_back(bin.p_W_floor.head<2>() + p);
          }
        }
      }
    }
  }
  return points;
}

const Bin& BinNamed(const CellLayout& layout, const std::string& bin) {
  const auto found = layout.bins.find(bin);
  if (found == layout.bins.end()) throw std::invalid_argument("cell layout: no bin '" + bin + "'");
  return found->second;
}

Eigen::Vector3d BinSlot(const CellLayout& layout, const std::string& bin, int filled) {
  const Bin& b = BinNamed(layout, bin);
  if (layout.bin_slots.empty()) return b.p_W_floor;
  const Eigen::Vector2d room = (b.inner_half.array() - layout.bin_slot_inset).max(0.0);
  const Eigen::Vector2d slot = layout.bin_slots[filled % layout.bin_slots.size()].cwiseProduct(room);
  return b.p_W_floor + Eigen::Vector3d(slot.x(), slot.y(), 0);
}

}  // namespace sortcell::cell
