#pragma once
/// @file
/// The box of a PCL octree over points, as PCL 1.13 fits it, so that code reproducing PCL's voxels gets
/// PCL's voxel keys.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>

namespace sortcell::perception {

/// Voxel keys packed x, y, z into one integer, 21 bits each (2^21 voxels a side: 15 km at 7.5 mm), so that
/// sorted keys order voxels by x, y, then z and a column's cells along z are one run.
constexpr int kPackedKeyBits = 21;
inline std::uint64_t PackKey(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return (x << (2 * kPackedKeyBits)) | (y << kPackedKeyBits) | z;
}

/// A voxel's integer key (x, y, z) in an octree.
using VoxelKey = std::array<std::uint32_t, 3>;

/// A PCL octree's box: its corner, its far side (exclusive) and its depth (2^depth voxels a side).
struct OctreeBox {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
  int depth = 0;
};

/// The box pcl::octree::OctreePointCloud fits to the extent [low, high] of an empty octree with voxels
/// `resolution` wide (defineBoundingBox, then getKeyBitSize): the smallest power-of-two cube of voxels
/// that holds the extent, grown evenly on each side, in double as PCL computes it.
OctreeBox PclOctreeBox(const Eigen::Vector3d& low, const Eigen::Vector3d& high, double resolution);

/// The box after PCL's octree grew to take `p` in (OctreePointCloud::adoptBoundingBoxToPoint: each growth
/// doubles the cube away from the side `p` lies beyond); an empty octree's (`box` none) is first centred on
/// `p`, one voxel wide, then fitted as above. Returns how many voxels the keys of what the octree held
/// moved along each axis (the old cube becomes a child of the new one, the last of a side it grew below).
/// Stops growing at 2^30 voxels a side.
std::array<std::uint32_t, 3> PclGrowOctreeBox(const Eigen::Vector3f& p, double resolution,
                                              std::optional<OctreeBox>& box);

/// The key of `p` in an octree with `box` (OctreePointCloud::genOctreeKeyforPoint, in double); false where
/// `p` lies outside the box's cube.
bool PclOctreeKey(const Eigen::Vector3f& p, const OctreeBox& box, double resolution, VoxelKey& key);

/// The rank of `key` in the order PCL's octrees visit their leaves (depth first, children by index
/// x << 2 | y << 1 | z): the key's bits interleaved from the top. For keys under 2^kPackedKeyBits.
std::uint64_t PclLeafOrder(const VoxelKey& key);

}  // namespace sortcell::perception
