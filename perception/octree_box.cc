#include "perception/octree_box.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sortcell::perception {

OctreeBox PclOctreeBox(const Eigen::Vector3d& low, const Eigen::Vector3d& high, double resolution) {
  const double min_value = std::numeric_limits<float>::epsilon();
  OctreeBox box{low.cwiseMin(high), low.cwiseMax(high), 0};
  std::uint32_t max_voxels = 2;
  for (int a = 0; a < 3; ++a) {
    // Clamped before the cast (PCL's own cast overflows past 2^32 voxels; no caller uses such a box).
    const double voxels = std::min(std::ceil((box.max[a] - box.min[a] - min_value) / resolution), 4294967295.0);
    max_voxels = std::max(max_voxels, static_cast<std::uint32_t>(voxels));
  }
  box.depth = static_cast<int>(std::min(32.0, std::ceil(std::log2(max_voxels) - min_value)));
  const double side = std::ldexp(1.0, box.depth) * resolution;  // PCL's (1 << depth), for any depth.
  for (int a = 0; a < 3; ++a) {
    const double oversize = (side - (box.max[a] - box.min[a])) / 2.0;
    if (oversize > min_value) box.min[a] -= oversize, box.max[a] += oversize;
  }
  return box;
}

std::array<std::uint32_t, 3> PclGrowOctreeBox(const Eigen::Vector3f& p, double resolution,
                                              std::optional<OctreeBox>& box) {
  const double min_value = std::numeric_limits<float>::epsilon();
  std::array<std::uint32_t, 3> moved{0, 0, 0};
  if (!box) {
    const Eigen::Vector3d centre = p.cast<double>();
    box = PclOctreeBox(centre.array() - resolution / 2, centre.array() + resolution / 2, resolution);
  }
  // Past 2^30 voxels a side the box is of no use to its callers (PCL's own would overflow its keys).
  while (box->depth < 30) {
    bool below = false, beyond[3];
    for (int a = 0; a < 3; ++a) {
      below = below || p[a] < box->min[a];
      beyond[a] = p[a] >= box->max[a];
    }
    if (!below && !beyond[0] && !beyond[1] && !beyond[2]) break;
    const double side = std::ldexp(1.0, box->depth) * resolution;
    for (int a = 0; a < 3; ++a) {
      if (!beyond[a]) box->min[a] -= side, moved[a] += 1u << box->depth;
    }
    ++box->depth;
    const double grown = std::ldexp(1.0, box->depth) * resolution - min_value;
    for (int a = 0; a < 3; ++a) box->max[a] = box->min[a] + grown;
  }
  return moved;
}

bool PclOctreeKey(const Eigen::Vector3f& p, const OctreeBox& box, double resolution, VoxelKey& key) {
  for (int a = 0; a < 3; ++a) {
    const double k = (static_cast<double>(p[a]) - box.min[a]) / resolution;
    if (!(k >= 0) || k >= std::ldexp(1.0, box.depth)) return false;
    key[a] = static_cast<std::uint32_t>(k);
  }
  return true;
}

std::uint64_t PclLeafOrder(const VoxelKey& key) {
  std::uint64_t code = 0;
  for (int b = kPackedKeyBits - 1; b >= 0; --b) {
    code = (code << 3) | ((key[0] >> b) & 1u) << 2 | ((key[1] >> b) & 1u) << 1 | ((key[2] >> b) & 1u);
  }
  return code;
}

}  // namespace sortcell::perception
