#include "perception/supervoxels.h"

#include "perception/normal_estimation.h"
#include "perception/octree_box.h"
#include "perception/pcl_adjacency_grid.h"
#include "perception/supervoxel_normals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <utility>

namespace sortcell::perception {
namespace {

// pcl::SupervoxelClustering<PointT>::VoxelData, in the same Eigen types so that the same expressions
// round alike; owner: the supervoxel's index, -1 for none.
struct VoxelData {
  Eigen::Vector3f xyz = Eigen::Vector3f::Zero();
  Eigen::Vector3f rgb = Eigen::Vector3f::Zero();
  Eigen::Vector4f normal = Eigen::Vector4f::Zero();
  float distance = std::numeric_limits<float>::max();
  int owner = -1;
};

// SupervoxelClustering::voxelDataDistance, expression for expression.
float Distance(const VoxelData& v1, const VoxelData& v2, const SupervoxelSettings& s) {
  const float spatial_dist = (v1.xyz - v2.xyz).norm() / s.seed_m;
  const float color_dist = (v1.rgb - v2.rgb).norm() / 255.0f;
  const float cos_angle_normal = 1.0f - std::abs(v1.normal.dot(v2.normal));
  return cos_angle_normal * s.normal_importance + color_dist * s.colour_importance +
         spatial_dist * s.spatial_importance;
}

// PCL's adjacency octree with each leaf's voxel data (PCL's idx_ is the index).
struct AdjacencyGrid {
  PclAdjacencyGrid leaves;
  std::vector<VoxelData> voxels;
};

// SupervoxelClustering::computeVoxelData with a normal cloud: each leaf's normal the normalised sum of its
// points' normals in input order. `normals` null: the normal cloud SupervoxelVoxelNormals would give (each
// of a leaf's points the leaf's normal), computed on this grid.
bool MakeAdjacencyGrid(const Cloud& points, const pcl::PointCloud<pcl::Normal>* normals, double resolution,
                       AdjacencyGrid& grid) {
  if (!MakePclAdjacencyGrid(points, resolution, grid.leaves)) return false;
  const PclAdjacencyGrid& leaves = grid.leaves;
  grid.voxels.resize(leaves.keys.size());
  for (size_t v = 0; v < grid.voxels.size(); ++v)
    grid.voxels[v].xyz = leaves.xyz[v], grid.voxels[v].rgb = leaves.rgb[v];
  if (normals) {
    for (size_t i = 0; i < points.size(); ++i) {
      grid.voxels[leaves.of_point[i]].normal += (*normals)[i].getNormalVector4fMap();
    }
  } else {
    const std::vector<pcl::Normal> of_leaf = PclVoxelNormals(leaves.xyz, leaves.neighbours, leaves.first_in_key_order);
    for (size_t v = 0; v < grid.voxels.size(); ++v) {
      for (int k = 0; k < leaves.count[v]; ++k) grid.voxels[v].normal += of_leaf[v].getNormalVector4fMap();
    }
  }
  for (VoxelData& v : grid.voxels) v.normal.normalize();
  return true;
}

// FLANN's L2_Simple distance, in float, summed axis by axis.
float SquaredDistance(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  float result = 0;
  for (int k = 0; k < 3; ++k) {
    const float diff = a[k] - b[k];
    result += diff * diff;
  }
  return result;
}

// The voxel centroids bucketed by the seed octree's cells, for searches within one cell of a point.
struct SeedCells {
  OctreeBox box;
  std::vector<VoxelKey> key_of_voxel;
  std::vector<std::pair<std::uint64_t, int>> voxels_by_cell;  // Packed cell key, voxel; sorted.
  std::vector<VoxelKey> occupied;                             // In the seed octree's leaf order.
};

// The seed octree (OctreePointCloudSearch over the voxel centroids in leaf order): its box grown point by
// point as PCL grows it, each centroid's key as PCL gave it when the point went in, moved with the cube as it
// grew since.
bool MakeSeedCells(const AdjacencyGrid& grid, double resolution, SeedCells& cells) {
  std::optional<OctreeBox> box;
  std::vector<VoxelKey>& keys = cells.key_of_voxel;
  keys.reserve(grid.voxels.size());
  for (const VoxelData& v : grid.voxels) {
    const std::array<std::uint32_t, 3> moved = PclGrowOctreeBox(v.xyz, resolution, box);
    if (box->depth >= kPackedKeyBits) return false;  // Cells around a key stay inside a packed key's field.
    if (moved != std::array<std::uint32_t, 3>{0, 0, 0}) {
      for (VoxelKey& k : keys) {
        for (int a = 0; a < 3; ++a) k[a] += moved[a];
      }
    }
    keys.emplace_back();
    if (!PclOctreeKey(v.xyz, *box, resolution, keys.back())) return false;
  }
  if (!box) return false;  // No voxels.
  cells.box = *box;
  std::vector<std::pair<std::uint64_t, VoxelKey>> occupied;
  for (size_t v = 0; v < keys.size(); ++v) {
    cells.voxels_by_cell.emplace_back(PackKey(keys[v][0], keys[v][1], keys[v][2]), static_cast<int>(v));
    occupied.emplace_back(PclLeafOrder(keys[v]), keys[v]);
  }
  std::sort(cells.voxels_by_cell.begin(), cells.voxels_by_cell.end());
  std::sort(occupied.begin(), occupied.end());
  occupied.erase(std::unique(occupied.begin(), occupied.end()), occupied.end());
  for (const auto& [order, k] : occupied) cells.occupied.push_back(k);
  return true;
}

// Calls visit(voxel) for every voxel in the cells around `k` (itself and its 26 neighbours).
template <typename Visit>
void ForVoxelsAround(const SeedCells& cells, const VoxelKey& k, Visit&& visit) {
  for (std::uint32_t x = k[0] - (k[0] > 0); x <= k[0] + 1; ++x) {
    for (std::uint32_t y = k[1] - (k[1] > 0); y <= k[1] + 1; ++y) {
      const std::uint64_t first = PackKey(x, y, k[2] - (k[2] > 0)), last = PackKey(x, y, k[2] + 1);
      for (auto it =
               std::lower_bound(cells.voxels_by_cell.begin(), cells.voxels_by_cell.end(), std::make_pair(first, -1));
           it != cells.voxels_by_cell.end() && it->first <= last; ++it) {
        visit(it->second);
      }
    }
  }
}

// SupervoxelClustering::selectInitialSupervoxelSeeds: for each occupied cell of the seed octree, the voxel
// nearest its centre (within one cell: the cell holds a centroid nearer than its width), kept when more
// than a share of the voxels a disc of half a cell would hold lie within half a cell of it. Empty when a
// centre's two nearest voxels are equally near to rounding, or a count may hang on rounding at the radius.
std::optional<std::vector<int>> Seeds(const AdjacencyGrid& grid, const SupervoxelSettings& s) {
  SeedCells cells;
  const double resolution = s.seed_m;
  if (!MakeSeedCells(grid, resolution, cells)) return std::nullopt;
  std::vector<int> nearest;
  for (const VoxelKey& k : cells.occupied) {
    Eigen::Vector3f centre;
    for (int a = 0; a < 3; ++a) {
      centre[a] = static_cast<float>((static_cast<double>(k[a]) + 0.5f) * resolution + cells.box.min[a]);
    }
    // The nearest and the second nearest: where the two are within rounding of each other, FLANN's k-d tree,
    // which prunes on bounds that round too, might pick either.
    float best = std::numeric_limits<float>::max(), second = best;
    int best_voxel = -1;
    ForVoxelsAround(cells, k, [&](int v) {
      const float d = SquaredDistance(centre, grid.voxels[v].xyz);
      if (d < best)
        second = best, best = d, best_voxel = v;
      else if (d < second)
        second = d;
    });
    if (best_voxel < 0 || second - best <= 1e-6f * best) return std::nullopt;
    nearest.push_back(best_voxel);
  }
  const float search_radius = 0.5f * s.seed_m;
  const float min_points = 0.05f * (search_radius) * (search_radius)*3.1415926536f / (s.voxel_m * s.voxel_m);
  // Each seed finds itself within the radius: with min_points under 1 every seed is kept, uncounted.
  if (min_points < 1) return nearest;
  const auto radius2 = static_cast<float>(static_cast<double>(search_radius) * search_radius);
  std::vector<int> kept;
  for (int seed : nearest) {
    const VoxelKey& k = cells.key_of_voxel[seed];
    int within = 0;
    bool near_edge = false;
    ForVoxelsAround(cells, k, [&](int v) {
      const float d = SquaredDistance(grid.voxels[seed].xyz, grid.voxels[v].xyz);
      within += d < radius2;
      near_edge = near_edge || std::abs(d - radius2) <= 1e-6f * radius2;
    });
    if (near_edge) return std::nullopt;
    if (static_cast<float>(within) > min_points) kept.push_back(seed);
  }
  return kept;
}

// SupervoxelClustering::SupervoxelHelper: its voxels in PCL's leaf order (PCL keeps them in a std::set
// ordered by idx_) and its centre.
struct Helper {
  std::uint32_t label = 0;
  std::vector<int> leaves;
  VoxelData centroid;  // Zero until the first update: PCL's first round measures from it, as here.
  bool alive = true;
};

void RemoveLeaf(Helper& helper, int v) {
  const auto it = std::lower_bound(helper.leaves.begin(), helper.leaves.end(), v);
  if (it != helper.leaves.end() && *it == v) helper.leaves.erase(it);
}

// SupervoxelHelper::expand: every neighbour of its voxels that is nearer its centre than to the centre
// that last claimed it is taken over.
void Expand(int h, std::vector<Helper>& helpers, AdjacencyGrid& grid, const SupervoxelSettings& s,
            std::vector<int>& taken, std::vector<int>& tried, int stamp) {
  taken.clear();
  Helper& helper = helpers[h];
  for (int leaf : helper.leaves) {
    for (int n : grid.leaves.neighbours.Of(leaf)) {
      VoxelData& voxel = grid.voxels[n];
      // A voxel this expansion measured already and did not take it would not take now: the same
      // centre, and only this expansion's takings lower a distance.
      if (voxel.owner == h || tried[n] == stamp) continue;
      tried[n] = stamp;
      const float dist = Distance(helper.centroid, voxel, s);
      if (!(dist < voxel.distance)) continue;
      voxel.distance = dist;
      if (voxel.owner >= 0) RemoveLeaf(helpers[voxel.owner], n);
      voxel.owner = h;
      taken.push_back(n);
    }
  }
  std::sort(taken.begin(), taken.end());
  std::vector<int> merged;
  merged.reserve(helper.leaves.size() + taken.size());
  std::set_union(helper.leaves.begin(), helper.leaves.end(), taken.begin(), taken.end(), std::back_inserter(merged));
  helper.leaves = std::move(merged);
}

// SupervoxelHelper::updateCentroid: the means of its voxels, summed in leaf order.
void UpdateCentroid(Helper& helper, const AdjacencyGrid& grid) {
  VoxelData& c = helper.centroid;
  c.normal = Eigen::Vector4f::Zero();
  c.xyz = Eigen::Vector3f::Zero();
  c.rgb = Eigen::Vector3f::Zero();
  for (int leaf : helper.leaves) {
    c.normal += grid.voxels[leaf].normal;
    c.xyz += grid.voxels[leaf].xyz;
    c.rgb += grid.voxels[leaf].rgb;
  }
  c.normal.normalize();
  c.xyz /= static_cast<float>(helper.leaves.size());
  c.rgb /= static_cast<float>(helper.leaves.size());
}

std::vector<Helper> Grow(const std::vector<int>& seeds, AdjacencyGrid& grid, const SupervoxelSettings& s) {
  std::vector<Helper> helpers(seeds.size());
  for (size_t i = 0; i < seeds.size(); ++i) {
    helpers[i].label = static_cast<std::uint32_t>(i + 1);
    helpers[i].leaves.push_back(seeds[i]);
    grid.voxels[seeds[i]].owner = static_cast<int>(i);  // A seed shared with an earlier one stays in both.
  }
  const int depth = static_cast<int>(1.8f * s.seed_m / s.voxel_m);
  std::vector<int> taken, tried(grid.voxels.size(), -1);
  int stamp = 0;
  for (int round = 1; round < depth; ++round) {
    for (size_t h = 0; h < helpers.size(); ++h) {
      if (helpers[h].alive) Expand(static_cast<int>(h), helpers, grid, s, taken, tried, stamp++);
    }
    for (Helper& helper : helpers) {
      if (!helper.alive) continue;
      if (helper.leaves.empty()) {
        helper.alive = false;
        continue;
      }
      UpdateCentroid(helper, grid);
    }
  }
  return helpers;
}

SupervoxelGraph GraphOf(const std::vector<Helper>& helpers, const AdjacencyGrid& grid) {
  SupervoxelGraph graph;
  for (size_t h = 0; h < helpers.size(); ++h) {
    const Helper& helper = helpers[h];
    if (!helper.alive) continue;
    auto sv = std::make_shared<pcl::Supervoxel<PointT>>();
    const VoxelData& c = helper.centroid;
    sv->centroid_.x = c.xyz[0], sv->centroid_.y = c.xyz[1], sv->centroid_.z = c.xyz[2];
    sv->centroid_.rgba = static_cast<std::uint32_t>(c.rgb[0]) << 16 | static_cast<std::uint32_t>(c.rgb[1]) << 8 |
                         static_cast<std::uint32_t>(c.rgb[2]);
    sv->normal_.normal_x = c.normal[0], sv->normal_.normal_y = c.normal[1], sv->normal_.normal_z = c.normal[2];
    sv->normal_.curvature = 0;  // PCL's centre keeps the curvature it was made with.
    graph.supervoxels[helper.label] = std::move(sv);
    std::set<std::uint32_t> neighbour_labels;
    for (int leaf : helper.leaves) {
      for (int n : grid.leaves.neighbours.Of(leaf)) {
        const int owner = grid.voxels[n].owner;
        if (owner >= 0 && owner != static_cast<int>(h)) neighbour_labels.insert(helpers[owner].label);
      }
    }
    for (std::uint32_t other : neighbour_labels) graph.adjacency.emplace(helper.label, other);
  }
  graph.label_of_point.reserve(grid.leaves.of_point.size());
  for (int v : grid.leaves.of_point) {
    const int owner = grid.voxels[v].owner;
    graph.label_of_point.push_back(owner >= 0 ? helpers[owner].label : 0);
  }
  return graph;
}

// Both forms of ExtractSupervoxels: `normals` null for the normals computed on the grid.
std::optional<SupervoxelGraph> Extract(const Cloud& points, const pcl::PointCloud<pcl::Normal>* normals,
                                       const SupervoxelSettings& settings) {
  AdjacencyGrid grid;
  // PCL's resolutions are the floats it was given, widened to double.
  if (points.empty() || !MakeAdjacencyGrid(points, normals, settings.voxel_m, grid)) return std::nullopt;
  const std::optional<std::vector<int>> seeds = Seeds(grid, settings);
  if (!seeds) return std::nullopt;
  return GraphOf(Grow(*seeds, grid, settings), grid);
}

}  // namespace

std::optional<SupervoxelGraph> ExtractSupervoxels(const Cloud& points, const pcl::PointCloud<pcl::Normal>& normals,
                                                  const SupervoxelSettings& settings) {
  if (normals.size() != points.size()) return std::nullopt;
  return Extract(points, &normals, settings);
}

std::optional<SupervoxelGraph> ExtractSupervoxels(const Cloud& points, const SupervoxelSettings& settings) {
  return Extract(points, nullptr, settings);
}

SupervoxelGraph PclSupervoxels(const Cloud::Ptr& points, const pcl::PointCloud<pcl::Normal>::ConstPtr& normals,
                               const SupervoxelSettings& settings) {
  pcl::SupervoxelClustering<PointT> clustering(settings.voxel_m, settings.seed_m);
  // The input is unorganized (voxel centres): no single-camera depth transform.
  clustering.setUseSingleCameraTransform(false);
  clustering.setInputCloud(points);
  if (normals && !normals->empty()) clustering.setNormalCloud(normals);
  clustering.setColorImportance(settings.colour_importance);
  clustering.setSpatialImportance(settings.spatial_importance);
  clustering.setNormalImportance(settings.normal_importance);
  SupervoxelGraph graph;
  clustering.extract(graph.supervoxels);
  clustering.getSupervoxelAdjacency(graph.adjacency);
  // getLabeledCloud keeps the input's order: point i of it is point i (label 0: none).
  const pcl::PointCloud<pcl::PointXYZL>::Ptr labelled = clustering.getLabeledCloud();
  graph.label_of_point.reserve(labelled->size());
  for (const pcl::PointXYZL& p : *labelled) graph.label_of_point.push_back(p.label);
  return graph;
}

}  // namespace sortcell::perception
