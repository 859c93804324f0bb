// The grid's radius neighbours against FLANN's (the same sets), and the normals they give.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include <pcl/features/impl/normal_3d.hpp>  // PCL's estimator, instantiated here: only this test uses it.
#include <pcl/search/kdtree.h>

#include "perception/normal_estimation.h"

namespace sortcell::perception {
namespace {

// `n` points scattered in a box with a corner at `low`, a few of them repeated (two points in one place).
Cloud RandomCloud(int n, const Eigen::Vector3f& low, float size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, size);
  Cloud cloud;
  for (int i = 0; i < n; ++i) {
    PointT p;
    p.getVector3fMap() = low + Eigen::Vector3f(u(rng), u(rng), u(rng));
    cloud.push_back(p);
    if (i % 50 == 0) cloud.push_back(p);
  }
  return cloud;
}

std::vector<std::vector<int>> Sorted(std::vector<std::vector<int>> sets) {
  for (auto& s : sets) std::sort(s.begin(), s.end());
  return sets;
}

std::vector<std::vector<int>> Sorted(const NeighbourLists& lists) {
  std::vector<std::vector<int>> sets;
  for (size_t i = 0; i < lists.size(); ++i) sets.emplace_back(lists.Of(i).begin(), lists.Of(i).end());
  return Sorted(sets);
}

TEST(GridNeighbourhoods, TheSameSetsAsFlann) {
  for (const float radius : {0.005f, 0.01f, 0.015f}) {
    const Cloud cloud = RandomCloud(3000, Eigen::Vector3f(-0.2f, -0.1f, 0.6f), 0.06f, 7);
    const NeighbourLists lists = GridNeighbourhoods(cloud, radius).neighbours;
    const auto grid = Sorted(lists);
    const auto flann = Sorted(RadiusNeighbours(cloud, radius));
    ASSERT_EQ(grid.size(), cloud.size());
    for (size_t i = 0; i < lists.size(); ++i) ASSERT_EQ(*lists.Of(i).begin(), static_cast<int>(i)) << "itself first";
    size_t pairs = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_EQ(grid[i], flann[i]) << "point " << i << " radius " << radius;
      pairs += grid[i].size();
    }
    EXPECT_GT(pairs, 2 * cloud.size()) << "radius " << radius << ": the test needs points with neighbours";
  }
}

TEST(GridNeighbourhoods, PointsSpreadFarApartFallBackToFlann) {
  Cloud cloud = RandomCloud(200, Eigen::Vector3f(0, 0, 0), 0.05f, 3);
  PointT far;
  far.getVector3fMap() = Eigen::Vector3f(1e5f, 0, 0);  // 10^7 radii away: beyond the grid's 2^21 cells.
  cloud.push_back(far);
  EXPECT_EQ(Sorted(GridNeighbourhoods(cloud, 0.01).neighbours), Sorted(RadiusNeighbours(cloud, 0.01)));
  EXPECT_TRUE(GridNeighbourhoods(Cloud(), 0.01).neighbours.empty());
}

TEST(EstimateNormals, APlaneSeenFromTheCameraFacesIt) {
  Cloud plane;  // z = 1 m, 5 mm apart, facing the camera at the origin: normal (0, 0, -1).
  for (int x = -20; x <= 20; ++x) {
    for (int y = -20; y <= 20; ++y) {
      PointT p;
      p.getVector3fMap() = Eigen::Vector3f(0.005f * x, 0.005f * y, 1.0f);
      plane.push_back(p);
    }
  }
  const pcl::PointCloud<pcl::Normal> normals = EstimateNormals(plane, 0.015);
  ASSERT_EQ(normals.size(), plane.size());
  for (const pcl::Normal& n : normals) EXPECT_NEAR(n.normal_z, -1.0f, 1e-5f);
}

// A cylinder 4 cm in radius, 1 m from the camera, its points 5 mm apart with a millimetre of noise.
Cloud NoisyCylinder() {
  std::mt19937 rng(11);
  std::normal_distribution<float> noise(0, 0.001f);
  Cloud cloud;
  for (int a = 0; a < 50; ++a) {
    for (int h = 0; h < 30; ++h) {
      const float angle = 3.14159f * a / 50;  // The half facing the camera.
      PointT p;
      p.getVector3fMap() = Eigen::Vector3f(0.04f * std::cos(angle), 0.005f * h, 1.0f - 0.04f * std::sin(angle)) +
                           Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
      cloud.push_back(p);
    }
  }
  return cloud;
}

// The grid's moments, the lists' and PCL's own estimator: one normal and curvature, up to rounding.
TEST(EstimateNormals, PclsNormalsUpToRounding) {
  const Cloud cloud = NoisyCylinder();
  const float radius = 0.012f;
  pcl::NormalEstimation<PointT, pcl::Normal> estimator;
  estimator.setInputCloud(std::make_shared<Cloud>(cloud));
  estimator.setSearchMethod(std::make_shared<pcl::search::KdTree<PointT>>());
  estimator.setRadiusSearch(radius);
  estimator.setViewPoint(0, 0, 0);
  pcl::PointCloud<pcl::Normal> pcl_normals;
  estimator.compute(pcl_normals);
  const Neighbourhoods grid = GridNeighbourhoods(cloud, radius);
  const pcl::PointCloud<pcl::Normal> estimated = EstimateNormals(cloud, radius);
  const pcl::PointCloud<pcl::Normal> from_lists = NormalsFromNeighbours(cloud, RadiusNeighbours(cloud, radius));
  ASSERT_EQ(pcl_normals.size(), cloud.size());
  int compared = 0;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const pcl::Normal& expected = pcl_normals[i];
    if (!std::isfinite(expected.normal_x)) continue;
    for (const pcl::Normal* n : {&grid.normals[i], &estimated[i], &from_lists[i]}) {
      EXPECT_GT(n->getNormalVector3fMap().dot(expected.getNormalVector3fMap()), 1 - 1e-5f) << "point " << i;
      EXPECT_NEAR(n->curvature, expected.curvature, 1e-4f) << "point " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, 1400);
}

}  // namespace
}  // namespace sortcell::perception
