// The grid's radius neighbours against FLANN's (the same sets), and the normals they give.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

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

TEST(GridRadiusNeighbours, TheSameSetsAsFlann) {
  for (const float radius : {0.005f, 0.01f, 0.015f}) {
    const Cloud cloud = RandomCloud(3000, Eigen::Vector3f(-0.2f, -0.1f, 0.6f), 0.06f, 7);
    const auto grid = Sorted(GridRadiusNeighbours(cloud, radius));
    const auto flann = Sorted(RadiusNeighbours(cloud, radius));
    ASSERT_EQ(grid.size(), cloud.size());
    size_t pairs = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_EQ(grid[i], flann[i]) << "point " << i << " radius " << radius;
      pairs += grid[i].size();
    }
    EXPECT_GT(pairs, 2 * cloud.size()) << "radius " << radius << ": the test needs points with neighbours";
  }
}

TEST(GridRadiusNeighbours, PointsSpreadFarApartFallBackToFlann) {
  Cloud cloud = RandomCloud(200, Eigen::Vector3f(0, 0, 0), 0.05f, 3);
  PointT far;
  far.getVector3fMap() = Eigen::Vector3f(1e5f, 0, 0);  // 10^7 radii away: beyond the grid's 2^21 cells.
  cloud.push_back(far);
  EXPECT_EQ(Sorted(GridRadiusNeighbours(cloud, 0.01)), Sorted(RadiusNeighbours(cloud, 0.01)));
  EXPECT_TRUE(GridRadiusNeighbours(Cloud(), 0.01).empty());
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

}  // namespace
}  // namespace sortcell::perception
