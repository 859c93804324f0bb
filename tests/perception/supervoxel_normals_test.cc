// The voxel normals and the supervoxels computed here against PCL's own: the supervoxels come out the same.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>

#include <pcl/filters/voxel_grid.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include "perception/convex_segmentation.h"
#include "perception/pcd_io.h"
#include "perception/supervoxel_normals.h"
#include "perception/supervoxels.h"
#include "test_clouds.h"

namespace sortcell::perception {
namespace {

using sortcell_test::Point;

// `raw` on a voxel grid of 5 mm, as the segmentation voxelises.
Cloud::Ptr Voxelised(const Cloud& raw) {
  auto voxels = std::make_shared<Cloud>();
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(std::make_shared<Cloud>(raw));
  grid.setLeafSize(0.005f, 0.005f, 0.005f);
  grid.filter(*voxels);
  return voxels;
}

// A tabletop seen from 0.9 m, voxelised: a table patch, a cylinder, a sphere, two faces of a box meeting at
// an edge, jittered by up to 1 mm, and one point far from the rest (a voxel with no neighbour but itself).
Cloud::Ptr Scene() {
  Cloud raw = sortcell_test::CylinderFront(0.035, 0.12, 0.9, 200, 30, 30, -0.1);
  raw += sortcell_test::SphereFront(0.04, 0.95, 30, 200, 30);
  for (double x = -0.2; x <= 0.2; x += 0.002) {
    for (double z = 0.8; z <= 1.1; z += 0.002) raw.push_back(Point(x, 0.07, z, 90, 90, 90));  // The table.
  }
  for (double u = 0; u <= 0.08; u += 0.002) {
    for (double y = -0.05; y <= 0.05; y += 0.002) {
      raw.push_back(Point(0.1 + u, y, 0.85 + u, 30, 30, 200));  // A box's face, 45 degrees to the camera,
      raw.push_back(Point(0.1 - u, y, 0.85 + u, 30, 30, 200));  // and the face beside it.
    }
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-0.001f, 0.001f);
  for (PointT& p : raw) p.x += jitter(rng), p.y += jitter(rng), p.z += jitter(rng);
  raw.push_back(Point(0.5, -0.3, 1.4, 1, 2, 3));
  return Voxelised(raw);
}

using Supervoxels = std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr>;

// PCL's supervoxels under the convex clustering's settings (`normals` null: PCL computes them).
Supervoxels Extract(const Cloud::Ptr& cloud, const pcl::PointCloud<pcl::Normal>::Ptr& normals) {
  return PclSupervoxels(cloud, normals, SupervoxelSettings()).supervoxels;
}

TEST(SupervoxelVoxelNormals, TheSupervoxelsOfPclsOwnVoxelNormals) {
  const Cloud::Ptr cloud = Scene();
  const auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>(SupervoxelVoxelNormals(*cloud, 0.0075f));
  ASSERT_EQ(normals->size(), cloud->size());
  const Supervoxels own = Extract(cloud, nullptr), given = Extract(cloud, normals);
  ASSERT_GT(own.size(), 20u);
  ASSERT_EQ(own.size(), given.size());
  int voxels = 0;
  for (const auto& [label, sv] : own) {
    const auto other = given.find(label);
    ASSERT_NE(other, given.end()) << "supervoxel " << label;
    const pcl::Supervoxel<PointT>& b = *other->second;
    ASSERT_EQ(sv->voxels_->size(), b.voxels_->size()) << "supervoxel " << label;
    for (size_t k = 0; k < sv->voxels_->size(); ++k) {
      EXPECT_EQ((*sv->voxels_)[k].getVector3fMap(), (*b.voxels_)[k].getVector3fMap()) << "supervoxel " << label;
      const Eigen::Vector3f n_pcl = (*sv->normals_)[k].getNormalVector3fMap(),
                            n = (*b.normals_)[k].getNormalVector3fMap();
      if (!n_pcl.allFinite()) {  // The far point's voxel: a fit of one place, no normal either way.
        EXPECT_FALSE(n.allFinite()) << "supervoxel " << label << " voxel " << k << ": " << n.transpose();
        continue;
      }
      EXPECT_GT(n.dot(n_pcl), 1 - 1e-5f) << "supervoxel " << label << " voxel " << k << ": " << n.transpose()
                                         << " against PCL's " << n_pcl.transpose();
      ++voxels;
    }
  }
  EXPECT_GT(voxels, 1000);
}

TEST(SupervoxelVoxelNormals, EmptyForNoPointsOrPointsSpreadTooFar) {
  EXPECT_TRUE(SupervoxelVoxelNormals(Cloud(), 0.0075f).empty());
  Cloud far;
  far.push_back(Point(0, 0, 1, 1, 2, 3));
  far.push_back(Point(1e5, 0, 1, 1, 2, 3));  // 1.3e7 voxels away: beyond 2^21.
  EXPECT_TRUE(SupervoxelVoxelNormals(far, 0.0075f).empty());
}

// The same floats, bit for bit (a voxel alone has no normal: NaN in both).
bool Same(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool SameSupervoxel(const pcl::Supervoxel<PointT>& a, const pcl::Supervoxel<PointT>& b) {
  bool same = a.centroid_.rgba == b.centroid_.rgba && Same(a.normal_.curvature, b.normal_.curvature);
  for (int k = 0; k < 3; ++k) same = same && Same(a.centroid_.data[k], b.centroid_.data[k]);
  for (int k = 0; k < 3; ++k) same = same && Same(a.normal_.normal[k], b.normal_.normal[k]);
  return same;
}

// Every supervoxel's centre, colour and normal, the adjacency and every point's label.
void ExpectTheSameGraph(const SupervoxelGraph& pcl, const SupervoxelGraph& ours) {
  ASSERT_EQ(pcl.supervoxels.size(), ours.supervoxels.size());
  int differ = 0;
  for (const auto& [label, sv] : pcl.supervoxels) {
    const auto other = ours.supervoxels.find(label);
    ASSERT_NE(other, ours.supervoxels.end()) << "supervoxel " << label;
    if (SameSupervoxel(*sv, *other->second)) continue;
    if (differ++ == 0) {
      ADD_FAILURE() << "supervoxel " << label << ": " << other->second->centroid_ << " " << other->second->normal_
                    << " against PCL's " << sv->centroid_ << " " << sv->normal_;
    }
  }
  EXPECT_EQ(differ, 0) << "supervoxels unlike PCL's";
  EXPECT_EQ(pcl.adjacency, ours.adjacency);
  EXPECT_EQ(pcl.label_of_point, ours.label_of_point);
}

TEST(SupervoxelGraphs, PclsOwnBitForBit) {
  const Cloud::Ptr cloud = Scene();
  SupervoxelSettings convex;  // The convex clustering's settings.
  SupervoxelSettings other;   // Voxels and seeds whose seeds are counted before they are kept; colour weighed.
  other.voxel_m = 0.005f;
  other.colour_importance = 0.5f;
  other.normal_importance = 2;
  for (const SupervoxelSettings& settings : {convex, other}) {
    const auto normals =
        std::make_shared<pcl::PointCloud<pcl::Normal>>(SupervoxelVoxelNormals(*cloud, settings.voxel_m));
    const std::optional<SupervoxelGraph> ours = ExtractSupervoxels(*cloud, *normals, settings);
    ASSERT_TRUE(ours.has_value()) << "voxels of " << settings.voxel_m << " m";
    const SupervoxelGraph pcl = PclSupervoxels(cloud, normals, settings);
    EXPECT_GT(pcl.supervoxels.size(), 20u);
    EXPECT_GT(pcl.adjacency.size(), 40u);
    ExpectTheSameGraph(pcl, *ours);
    const std::optional<SupervoxelGraph> one_pass = ExtractSupervoxels(*cloud, settings);  // Normals on its grid.
    ASSERT_TRUE(one_pass.has_value());
    ExpectTheSameGraph(pcl, *one_pass);
  }
}

TEST(SupervoxelGraphs, PclsOwnOnARealCapture) {
  // A real tabletop (a bowl and a pot on a table, the room behind), voxelised as the segmentation does.
  const std::filesystem::path file =
      std::filesystem::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real" / "mosd-learn" / "learn36.pcd";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file << " beside this checkout";
  const Cloud::Ptr capture = LoadCloud(file, true);
  Cloud finite;
  for (const PointT& p : *capture) {
    if (p.getVector3fMap().allFinite()) finite.push_back(p);
  }
  const Cloud::Ptr cloud = Voxelised(finite);
  const SupervoxelSettings settings;
  const auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>(SupervoxelVoxelNormals(*cloud, settings.voxel_m));
  const std::optional<SupervoxelGraph> ours = ExtractSupervoxels(*cloud, *normals, settings);
  ASSERT_TRUE(ours.has_value());
  const SupervoxelGraph pcl = PclSupervoxels(cloud, normals, settings);
  EXPECT_GT(pcl.supervoxels.size(), 200u);
  ExpectTheSameGraph(pcl, *ours);
  const std::optional<SupervoxelGraph> one_pass = ExtractSupervoxels(*cloud, settings);
  ASSERT_TRUE(one_pass.has_value());
  ExpectTheSameGraph(pcl, *one_pass);
}

TEST(SupervoxelGraphs, TheConvexClustersOfPclsSupervoxels) {
  const Cloud::Ptr cloud = Scene();
  // Ours on this cloud (else both would be PCL's): the convex clustering's settings are SupervoxelSettings'.
  ASSERT_TRUE(ExtractSupervoxels(*cloud, SupervoxelSettings()).has_value());
  const Eigen::Vector4d plane_C(0, -1, 0, 0.07);  // The table at y = 0.07 m, the camera above it.
  ConvexClusteringParams ours, pcls;
  pcls.own_supervoxels = false;
  const std::vector<pcl::PointIndices> a = ConvexClusters(cloud, plane_C, ours),
                                       b = ConvexClusters(cloud, plane_C, pcls);
  EXPECT_GE(a.size(), 3u);
  ASSERT_EQ(a.size(), b.size());
  for (size_t c = 0; c < a.size(); ++c) EXPECT_EQ(a[c].indices, b[c].indices) << "cluster " << c;
}

TEST(SupervoxelGraphs, NoneWhereASeedCellsCentreHasTwoNearestVoxels) {
  // A flat lattice of points 1 cm apart, one to a voxel. The seed octree's cells (3 cm) start 3 cm below
  // the first point, so each cell's centre lies 1.5 cm past a point on both axes: midway between four
  // voxel centroids, and which one PCL's k-d tree takes is its own order's choice.
  Cloud lattice;
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j < 24; ++j) lattice.push_back(Point(0.005 + 0.01 * i, 0.005 + 0.01 * j, 1.0, 90, 90, 90));
  }
  pcl::PointCloud<pcl::Normal> up(lattice.size(), 1, pcl::Normal(0, 0, -1));
  EXPECT_FALSE(ExtractSupervoxels(lattice, up, SupervoxelSettings()).has_value());
}

TEST(SupervoxelGraphs, NoneWherePclsWouldHangOnWhatIsNotReproduced) {
  const Cloud::Ptr cloud = Scene();
  const SupervoxelSettings settings;
  const pcl::PointCloud<pcl::Normal> normals = SupervoxelVoxelNormals(*cloud, settings.voxel_m);
  EXPECT_FALSE(ExtractSupervoxels(Cloud(), pcl::PointCloud<pcl::Normal>(), settings).has_value());
  EXPECT_FALSE(ExtractSupervoxels(Cloud(), settings).has_value());
  pcl::PointCloud<pcl::Normal> fewer = normals;
  fewer.resize(normals.size() - 1);
  EXPECT_FALSE(ExtractSupervoxels(*cloud, fewer, settings).has_value()) << "a normal missing";
  Cloud with_nan = *cloud;
  with_nan[3].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(ExtractSupervoxels(with_nan, normals, settings).has_value()) << "a point not finite";
  EXPECT_FALSE(ExtractSupervoxels(with_nan, settings).has_value()) << "a point not finite";
  Cloud far;
  far.push_back(Point(0, 0, 1, 1, 2, 3));
  far.push_back(Point(1e5, 0, 1, 1, 2, 3));  // 1.3e7 voxels away: beyond 2^21.
  pcl::PointCloud<pcl::Normal> two(2, 1);
  EXPECT_FALSE(ExtractSupervoxels(far, two, settings).has_value()) << "points too far apart";
}

}  // namespace
}  // namespace sortcell::perception
