#include "cell/cell_layout.h"

#include <stdexcept>

namespace sortcell::cell {

Eigen::Vector3d BinSlot(const CellLayout& layout, const std::string& category, int filled) {
  const auto bin = layout.p_W_bin.find(category);
  if (bin == layout.p_W_bin.end()) throw std::invalid_argument("cell layout: no bin for category '" + category + "'");
  if (layout.bin_slots.empty()) return bin->second;
  return bin->second + layout.bin_slots[filled % layout.bin_slots.size()];
}

}  // namespace sortcell::cell
