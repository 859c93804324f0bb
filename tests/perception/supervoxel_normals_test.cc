// The voxel normals computed for PCL's supervoxels against PCL's own: the supervoxels come out the same.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>

#include <pcl/filters/voxel_grid.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include "perception/supervoxel_normals.h"
#include "test_clouds.h"

namespace sortcell::perception {
namespace {

using sortcell_test::Point;

// A tabletop seen from 0.9 m, voxelised at 5 mm as the segmentation does: a table patch, a cylinder, a
// sphere, two faces of a box meeting at an edge, jittered by up to 1 mm, and one point far from the rest
// (a voxel with no neighbour but itself).
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
  auto voxels = std::make_shared<Cloud>();
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(std::make_shared<Cloud>(raw));
  grid.setLeafSize(0.005f, 0.005f, 0.005f);
  grid.filter(*voxels);
  return voxels;
}

using Supervoxels = std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr>;

Supervoxels Extract(const Cloud::Ptr& cloud, const pcl::PointCloud<pcl::Normal>::Ptr& normals) {
  pcl::SupervoxelClustering<PointT> clustering(0.0075f, 0.03f);  // The convex clustering's settings.
  clustering.setUseSingleCameraTransform(false);
  clustering.setInputCloud(cloud);
  if (normals) clustering.setNormalCloud(normals);
  clustering.setColorImportance(0);
  clustering.setSpatialImportance(1);
  clustering.setNormalImportance(4);
  Supervoxels supervoxels;
  clustering.extract(supervoxels);
  return supervoxels;
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

}  // namespace
}  // namespace sortcell::perception
