/// @file
/// PCL's class templates that perception uses, instantiated here for its point type instead of taken
/// from PCL's prebuilt libraries (libpcl_segmentation, _features, _filters, _surface, _search, _sample_consensus,
/// _kdtree, _octree, which the binaries no longer load). Those libraries hold every point type's instantiation, and the
/// loader's symbol lookups in them cost each process about 0.1 s at start (`perf stat -r 20 sortcell --version`:
/// 0.16-0.17 s linked to them, 0.065 s with this file, one after the other on 2026-12-07; docs/performance.md, Process
/// start), in every sweep worker, every `sortcell` command and every test. The code is PCL's own (PCL_NO_PRECOMPILE
/// includes its implementation headers), compiled by this build's compiler with its flags. Compiled on its own, outside
/// the unity batches: the macro must reach no other file.
#define PCL_NO_PRECOMPILE
// GCC's flow analysis warns of PCL's and Eigen's code here (maybe-uninitialized), not of ours.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <pcl/features/cvfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_perpendicular_plane.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <pcl/search/organized.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/extract_polygonal_prism_data.h>
#include <pcl/segmentation/supervoxel_clustering.h>
#include <pcl/surface/convex_hull.h>

#include <cmath>
#include <cstdint>

template class pcl::search::Search<pcl::PointXYZRGB>;
template class pcl::search::KdTree<pcl::PointXYZRGB>;
template class pcl::search::OrganizedNeighbor<pcl::PointXYZRGB>;
template class pcl::KdTreeFLANN<pcl::PointXYZRGB>;
template class pcl::RandomSampleConsensus<pcl::PointXYZRGB>;
template class pcl::SampleConsensusModelPlane<pcl::PointXYZRGB>;
template class pcl::SampleConsensusModelPerpendicularPlane<pcl::PointXYZRGB>;
template class pcl::ConvexHull<pcl::PointXYZRGB>;
template class pcl::ExtractPolygonalPrismData<pcl::PointXYZRGB>;
template class pcl::EuclideanClusterExtraction<pcl::PointXYZRGB>;
template class pcl::VoxelGrid<pcl::PointXYZRGB>;
template class pcl::SupervoxelClustering<pcl::PointXYZRGB>;
template class pcl::CVFHEstimation<pcl::PointXYZRGB, pcl::Normal, pcl::VFHSignature308>;

// What PCL's headers declare and its libraries' sources define (segmentation/src/supervoxel_clustering.cpp,
// features/src/pfh.cpp): written here to the same arithmetic, operation for operation, so that supervoxels
// and descriptors come out as with PCL's libraries, bit for bit. Checked: the pair features against
// libpcl_features (unit PairFeatures.EqualPclsLibraryToTheBit); the descriptors of 176 simulated segments
// and 39 real RGB-D Object views, and every figure of the segmentation benchmark, the same as the build
// linked to PCL's libraries (2026-12-07, docs/performance.md, Process start).
namespace {
using VoxelData = pcl::SupervoxelClustering<pcl::PointXYZRGB>::VoxelData;
}  // namespace

// A voxel's sums: position in float, colour per channel in float (the 8-bit channels would overflow).
template <>
void pcl::octree::OctreePointCloudAdjacencyContainer<pcl::PointXYZRGB, VoxelData>::addPoint(
    const pcl::PointXYZRGB& new_point) {
  ++num_points_;
  data_.xyz_[0] += new_point.x;
  data_.xyz_[1] += new_point.y;
  data_.xyz_[2] += new_point.z;
  data_.rgb_[0] += static_cast<float>(new_point.r);
  data_.rgb_[1] += static_cast<float>(new_point.g);
  data_.rgb_[2] += static_cast<float>(new_point.b);
}

// The sums made means, each component divided by the point count in float.
template <>
void pcl::octree::OctreePointCloudAdjacencyContainer<pcl::PointXYZRGB, VoxelData>::computeData() {
  const auto count = static_cast<float>(num_points_);
  for (int k = 0; k < 3; ++k) data_.rgb_[k] /= count;
  for (int k = 0; k < 3; ++k) data_.xyz_[k] /= count;
}

// The voxel as a point: the mean colour truncated to 8 bits a channel (alpha 0), the mean position.
template <>
void pcl::SupervoxelClustering<pcl::PointXYZRGB>::VoxelData::getPoint(pcl::PointXYZRGB& point_arg) const {
  point_arg.rgba = static_cast<std::uint32_t>(rgb_[0]) << 16 | static_cast<std::uint32_t>(rgb_[1]) << 8 |
                   static_cast<std::uint32_t>(rgb_[2]);
  point_arg.x = xyz_[0];
  point_arg.y = xyz_[1];
  point_arg.z = xyz_[2];
}

// The four Darboux-frame features of a point pair (Rusu's PFH): the angle of n2 about the frame (f1), its
// component along v (f2), the cosine between the source normal and the line (f3), the distance (f4). The
// source is the point whose normal makes the smaller angle with the line between them. In 4-vectors with
// w = 0, as PCL computes them (Eigen's 4-float dot products sum in another order than 3-float ones).
bool pcl::computePairFeatures(const Eigen::Vector4f& p1, const Eigen::Vector4f& n1, const Eigen::Vector4f& p2,
                              const Eigen::Vector4f& n2, float& f1, float& f2, float& f3, float& f4) {
  Eigen::Vector4f line = p2 - p1;
  line[3] = 0.0f;
  f4 = line.norm();
  const auto degenerate = [&] {
    f1 = f2 = f3 = f4 = 0.0f;
    return false;
  };
  if (f4 == 0.0f) return degenerate();
  Eigen::Vector4f u = n1, other = n2;
  u[3] = other[3] = 0.0f;
  const float cos1 = u.dot(line) / f4, cos2 = other.dot(line) / f4;
  f3 = cos1;
  if (std::acos(std::fabs(cos1)) > std::acos(std::fabs(cos2))) {
    u = n2;
    other = n1;
    u[3] = other[3] = 0.0f;
    line *= (-1);
    f3 = -cos2;
  }
  Eigen::Vector4f v = line.cross3(u);
  v[3] = 0.0f;
  const float v_norm = v.norm();
  if (v_norm == 0.0f) return degenerate();
  v /= v_norm;
  Eigen::Vector4f w = u.cross3(v);
  v[3] = 0.0f;
  f2 = v.dot(other);
  w[3] = 0.0f;
  f1 = std::atan2(w.dot(other), u.dot(other));
  return true;
}
