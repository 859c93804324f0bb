// Segmentation on real labelled Kinect captures (mOSD, ../shared/real beside the checkout; skipped
// where it is absent): touching objects, scored against the capture's own labels.
#include <gtest/gtest.h>

#include <filesystem>

#include "perception/pcd_io.h"
#include "perception/segmentation.h"
#include "perception/segmentation_scoring.h"

namespace sortcell::perception {
namespace {

namespace fs = std::filesystem;

const fs::path kReal = fs::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real";

SegmentationScore Score(const fs::path& file, SegmentationParams::Clustering clustering) {
  const std::vector<int> truth = LoadMosdObjectIds(file);
  SegmentationParams params;
  params.clustering = clustering;
  const SegmentationResult result = SegmentObjects(*LoadCloud(file, true), std::nullopt, nullptr, params);
  std::vector<std::vector<int>> segments;
  for (const auto& s : result.segments) segments.push_back(s.indices);
  return ScoreSegmentation(truth, segments, 100);
}

TEST(SegmentationReal, ConvexClustersSeparateTouchingBoxesAndCansThatEuclideanMerges) {
  const fs::path file = kReal / "mosd-hard" / "test44.pcd";  // Five objects, touching in pairs.
  if (!fs::exists(file)) GTEST_SKIP() << "no " << file << " beside this checkout";
  const SegmentationScore euclidean = Score(file, SegmentationParams::Clustering::kEuclidean);
  const SegmentationScore convex = Score(file, SegmentationParams::Clustering::kConvex);
  EXPECT_EQ(euclidean.objects, 5);
  EXPECT_LE(euclidean.found, 3) << "Euclidean clusters merge the touching pairs";
  EXPECT_EQ(convex.found, 5);
  EXPECT_GT(convex.OverlapF(), 0.9);
}

TEST(SegmentationReal, ConvexClustersKeepStackedBoxesApartAndSingleBoxesWhole) {
  for (const char* name : {"learn0.pcd", "learn20.pcd"}) {  // Two boxes side by side; two boxes stacked.
    const fs::path file = kReal / "mosd-learn" / name;
    if (!fs::exists(file)) GTEST_SKIP() << "no " << file << " beside this checkout";
    const SegmentationScore convex = Score(file, SegmentationParams::Clustering::kConvex);
    EXPECT_EQ(convex.found, 2) << name;
    EXPECT_EQ(convex.split, 0) << name;
  }
}

TEST(SegmentationReal, ConvexClustersKeepHollowObjectsWholeInsideAndOut) {
  // A bowl and a pot whose floors are seen over the rim (learn36), a pot and a bowl upside down (learn37):
  // LCCP cuts each inside from its outside at the rim; the inside lies within the wall's circle and joins it.
  for (const char* name : {"learn36.pcd", "learn37.pcd"}) {
    const fs::path file = kReal / "mosd-learn" / name;
    if (!fs::exists(file)) GTEST_SKIP() << "no " << file << " beside this checkout";
    const SegmentationScore convex = Score(file, SegmentationParams::Clustering::kConvex);
    EXPECT_EQ(convex.objects, 3) << name;
    EXPECT_EQ(convex.found, 3) << name;
    EXPECT_EQ(convex.split, 0) << name;
  }
}

}  // namespace
}  // namespace sortcell::perception
