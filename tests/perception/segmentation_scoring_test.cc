#include "perception/segmentation_scoring.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <string>

namespace sortcell::perception {
namespace {

std::vector<int> Range(int from, int to) {  // Pixels [from, to).
  std::vector<int> v(to - from);
  std::iota(v.begin(), v.end(), from);
  return v;
}

// A 100-pixel frame: object 1 at pixels 0-19, object 2 at 20-39, object 3 at 60-69; the rest 0.
std::vector<int> Truth() {
  std::vector<int> t(100, 0);
  for (int i = 0; i < 20; ++i) t[i] = 1;
  for (int i = 20; i < 40; ++i) t[i] = 2;
  for (int i = 60; i < 70; ++i) t[i] = 3;
  return t;
}

TEST(SegmentationScoring, ExactSegmentsAreFoundWithFullOverlap) {
  const SegmentationScore s = ScoreSegmentation(Truth(), {Range(0, 20), Range(20, 40), Range(60, 70)});
  EXPECT_EQ(s.objects, 3);
  EXPECT_EQ(s.found, 3);
  EXPECT_DOUBLE_EQ(s.OverlapPrecision(), 1.0);
  EXPECT_DOUBLE_EQ(s.OverlapRecall(), 1.0);
  EXPECT_DOUBLE_EQ(s.OverlapF(), 1.0);
}

TEST(SegmentationScoring, TwoTouchingObjectsInOneSegmentAreMerged) {
  // Objects 1 and 2 in one segment: one of them is matched to it (IoU 0.5: found), the other is merged.
  const SegmentationScore s = ScoreSegmentation(Truth(), {Range(0, 40), Range(60, 70)});
  EXPECT_EQ(s.found, 2);
  EXPECT_EQ(s.merged, 1);
  EXPECT_EQ(s.matched_pixels, 30);  // One to one: the merged segment counts for one object only.
  EXPECT_DOUBLE_EQ(s.OverlapPrecision(), 30.0 / 50);
  EXPECT_DOUBLE_EQ(s.OverlapRecall(), 30.0 / 50);
}

TEST(SegmentationScoring, AnObjectInThreePiecesIsSplitAndOneNotSegmentedIsMissed) {
  const SegmentationScore s = ScoreSegmentation(Truth(), {Range(0, 7), Range(7, 14), Range(14, 20), Range(20, 40)});
  EXPECT_EQ(s.found, 1);
  EXPECT_EQ(s.split, 1);
  EXPECT_EQ(s.missed, 1);  // Object 3.
  EXPECT_EQ(s.segments, 4);
}

TEST(SegmentationScoring, SegmentPixelsOffEveryObjectCostPrecision) {
  const SegmentationScore s = ScoreSegmentation(Truth(), {Range(0, 20), Range(20, 40), Range(60, 70), Range(80, 100)});
  EXPECT_EQ(s.found, 3);
  EXPECT_DOUBLE_EQ(s.OverlapPrecision(), 50.0 / 70);
  EXPECT_DOUBLE_EQ(s.OverlapRecall(), 1.0);
}

TEST(SegmentationScoring, SmallObjectsAreNotCountedAndScoresPool) {
  const SegmentationScore s = ScoreSegmentation(Truth(), {Range(0, 20)}, 15);
  EXPECT_EQ(s.objects, 2);  // Object 3 has 10 pixels.
  EXPECT_EQ(s.true_pixels, 40);
  const SegmentationScore pooled = PoolScores({s, s});
  EXPECT_EQ(pooled.objects, 4);
  EXPECT_EQ(pooled.found, 2);
  EXPECT_EQ(pooled.missed, 2);
  EXPECT_DOUBLE_EQ(pooled.OverlapRecall(), s.OverlapRecall());
}

TEST(SegmentationScoring, APixelOutsideTheFrameIsAnError) {
  try {
    ScoreSegmentation(Truth(), {Range(95, 105)});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "segmentation scoring: segment 0 has pixel 100 outside the frame's 100");
  }
}

}  // namespace
}  // namespace sortcell::perception
