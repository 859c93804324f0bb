// Segments partly hidden behind a nearer one (perception/occlusion.h), on a synthetic depth image.
#include <gtest/gtest.h>

#include <limits>

#include "perception/occlusion.h"
#include "test_clouds.h"

namespace sortcell::perception {
namespace {

constexpr int kWidth = 40, kHeight = 20;

// A wall at 1.2 m; a far object (columns 5-19, 0.9 m) and a near one (columns 17-29, 0.7 m) in front
// of its right part, with a 2-pixel shadow of invalid depth at the near one's left edge.
struct OccludedScene {
  Cloud cloud;
  std::vector<Segment> segments{2};
};

OccludedScene FarBehindNear() {
  OccludedScene scene;
  scene.cloud.width = kWidth;
  scene.cloud.height = kHeight;
  scene.cloud.points.resize(kWidth * kHeight);
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      double z = 1.2;
      int segment = -1;
      if (r >= 5 && r < 15 && c >= 17 && c < 30)
        z = 0.7, segment = 1;
      else if (r >= 5 && r < 15 && c >= 5 && c < 15)
        z = 0.9, segment = 0;
      const int i = r * kWidth + c;
      scene.cloud.points[i] = sortcell_test::Point(0.01 * c, 0.01 * r, z, 100, 100, 100);
      if (r >= 5 && r < 15 && (c == 15 || c == 16)) scene.cloud.points[i].z = std::numeric_limits<float>::quiet_NaN();
      if (segment >= 0) scene.segments[segment].indices.push_back(i);
    }
  }
  return scene;
}

TEST(Occlusion, TheFarSegmentIsHiddenAtItsEdgeTowardsTheNearOne) {
  const OccludedScene scene = FarBehindNear();
  const std::vector<int> occluded = OccludedEdgePixels(scene.cloud, scene.segments);
  ASSERT_EQ(occluded.size(), 2u);
  EXPECT_EQ(occluded[0], 10);  // Its right column, rows 5-14, past the shadow.
  EXPECT_EQ(occluded[1], 0);   // The near one borders only what is behind it.
}

TEST(Occlusion, AWideShadowIsNotLookedPast) {
  const OccludedScene scene = FarBehindNear();
  OcclusionParams params;
  params.max_gap = 1;
  EXPECT_EQ(OccludedEdgePixels(scene.cloud, scene.segments, params)[0], 0);
}

TEST(Occlusion, MisuseThrows) {
  OccludedScene scene = FarBehindNear();
  scene.segments[0].indices.push_back(kWidth * kHeight);
  EXPECT_THROW(OccludedEdgePixels(scene.cloud, scene.segments), std::invalid_argument);
  Cloud unorganized = sortcell_test::SphereFront(0.03, 0.8, 1, 2, 3);
  EXPECT_THROW(OccludedEdgePixels(unorganized, {}), std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::perception
