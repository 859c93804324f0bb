#include "perception/convex_segmentation.h"

#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>
// LCCP's template bodies: PCL 1.13 does not instantiate it for every point type.
#include <pcl/segmentation/impl/lccp_segmentation.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <map>

namespace sortcell::perception {
namespace {

// A cluster's volume over the plane: its footprint (the convex hull of its voxels projected onto the
// plane, in plane coordinates) and its top (the largest height above the plane).
struct Volume {
  std::vector<cv::Point2f> hull;
  float top = 0;
};

struct PlaneFrame {
  Eigen::Vector3f n, u, v;
  float d = 0;
  cv::Point2f Project(const PointT& p) const {
    const Eigen::Vector3f x = p.getVector3fMap();
    return {u.dot(x), v.dot(x)};
  }
  float Height(const PointT& p) const { return n.dot(p.getVector3fMap()) + d; }
};

PlaneFrame MakePlaneFrame(const Eigen::Vector4d& plane_C) {
  PlaneFrame f;
  f.n = plane_C.head<3>().cast<float>().normalized();
  f.d = static_cast<float>(plane_C[3] / plane_C.head<3>().norm());
  f.u = f.n.unitOrthogonal();
  f.v = f.n.cross(f.u);
  return f;
}

Volume VolumeOf(const Cloud& voxels, const pcl::PointIndices& cluster, const PlaneFrame& frame) {
  std::vector<cv::Point2f> footprint;
  Volume volume;
  volume.top = -1e9f;
  for (int i : cluster.indices) {
    footprint.push_back(frame.Project(voxels[i]));
    volume.top = std::max(volume.top, frame.Height(voxels[i]));
  }
  cv::convexHull(footprint, volume.hull);
  return volume;
}

// Joins each cluster that lies mostly inside a larger one's volume to it (smallest first).
void JoinPiecesInsideOthers(const Cloud& voxels, const PlaneFrame& frame, const ConvexClusteringParams& params,
                            std::vector<pcl::PointIndices>& clusters) {
  std::vector<Volume> volumes;
  for (const auto& c : clusters) volumes.push_back(VolumeOf(voxels, c, frame));
  std::vector<bool> joined(clusters.size(), false);
  for (size_t a = clusters.size(); a-- > 1;) {  // Smallest first (clusters are sorted largest first); a piece joins a larger one.
    size_t best = a;
    double best_fraction = params.inside_fraction;
    for (size_t b = 0; b < a; ++b) {
      if (volumes[b].hull.size() < 3) continue;
      int inside = 0;
      for (int i : clusters[a].indices) {
        inside += frame.Height(voxels[i]) <= volumes[b].top + params.top_tolerance_m &&
                  cv::pointPolygonTest(volumes[b].hull, frame.Project(voxels[i]), false) >= 0;
      }
      const double fraction = static_cast<double>(inside) / clusters[a].indices.size();
      if (fraction >= best_fraction) best_fraction = fraction, best = b;
    }
    if (best == a) continue;
    clusters[best].indices.insert(clusters[best].indices.end(), clusters[a].indices.begin(), clusters[a].indices.end());
    joined[a] = true;
  }
  std::vector<pcl::PointIndices> kept;
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (!joined[c]) kept.push_back(std::move(clusters[c]));
  }
  clusters = std::move(kept);
}

}  // namespace

std::vector<pcl::PointIndices> ConvexClusters(const Cloud::Ptr& voxels, const Eigen::Vector4d& plane_C,
                                              const ConvexClusteringParams& params) {
  if (voxels->empty()) return {};
  pcl::SupervoxelClustering<PointT> supervoxels(static_cast<float>(params.voxel_m), static_cast<float>(params.seed_m));
  // The input is unorganized (voxel centres): no single-camera depth transform.
  supervoxels.setUseSingleCameraTransform(false);
  supervoxels.setInputCloud(voxels);
  supervoxels.setColorImportance(0.0f);
  supervoxels.setSpatialImportance(1.0f);
  supervoxels.setNormalImportance(4.0f);
  std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr> clusters;
  supervoxels.extract(clusters);
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  supervoxels.getSupervoxelAdjacency(adjacency);

  pcl::LCCPSegmentation<PointT> lccp;
  lccp.setConcavityToleranceThreshold(static_cast<float>(params.concavity_deg));
  lccp.setSanityCheck(true);
  lccp.setSmoothnessCheck(true, static_cast<float>(params.voxel_m), static_cast<float>(params.seed_m), 0.1f);
  lccp.setKFactor(0);
  lccp.setMinSegmentSize(3);
  lccp.setInputSupervoxels(clusters, adjacency);
  lccp.segment();
  pcl::PointCloud<pcl::PointXYZL>::Ptr labelled = supervoxels.getLabeledCloud();
  lccp.relabelCloud(*labelled);

  // getLabeledCloud keeps the input's order: point i of `labelled` is voxel i (label 0: none).
  std::map<std::uint32_t, pcl::PointIndices> by_label;
  for (size_t i = 0; i < labelled->size() && i < voxels->size(); ++i) {
    const std::uint32_t label = (*labelled)[i].label;
    if (label != 0) by_label[label].indices.push_back(static_cast<int>(i));
  }
  std::vector<pcl::PointIndices> out;
  for (auto& [label, indices] : by_label) out.push_back(std::move(indices));
  const auto larger = [](const pcl::PointIndices& a, const pcl::PointIndices& b) { return a.indices.size() > b.indices.size(); };
  std::sort(out.begin(), out.end(), larger);
  JoinPiecesInsideOthers(*voxels, MakePlaneFrame(plane_C), params, out);
  std::sort(out.begin(), out.end(), larger);
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&params](const pcl::PointIndices& c) {
                             const int n = static_cast<int>(c.indices.size());
                             return n < params.min_cluster_voxels || n > params.max_cluster_voxels;
                           }),
            out.end());
  return out;
}

}  // namespace sortcell::perception
