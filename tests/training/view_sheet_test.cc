// The view sheet (training/view_sheet.h): which samples a row shows, and how a view is drawn.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tests/error_of.h"
#include "training/view_sheet.h"

namespace training = sortcell::training;
namespace perception = sortcell::perception;

namespace {

training::Dataset Labelled(const std::vector<std::string>& instances) {
  training::Dataset d;
  for (const std::string& instance : instances) {
    training::Sample s;
    s.instance = instance;
    s.category = instance.substr(0, instance.find('_'));
    d.samples.push_back(s);
  }
  return d;
}

// A flat square of `side` m, `z` m in front of the camera, of one colour.
perception::Cloud::Ptr Square(double side, double z, uint8_t r, uint8_t g, uint8_t b, int n = 20) {
  auto cloud = std::make_shared<perception::Cloud>();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      perception::PointT p;
      p.x = static_cast<float>(side * (i / (n - 1.0) - 0.5));
      p.y = static_cast<float>(side * (j / (n - 1.0) - 0.5));
      p.z = static_cast<float>(z);
      p.r = r, p.g = g, p.b = b;
      cloud->push_back(p);
    }
  }
  return cloud;
}

}  // namespace

TEST(ViewSheet, ARowsViewsAreSpreadOverItsLabelsSamples) {
  const training::Dataset d = Labelled({"apple_1", "pear_1", "apple_1", "apple_2", "apple_2", "pear_1", "apple_2"});
  // The apples are samples 0, 2, 3, 4 and 6: two of them from the middle of each half.
  EXPECT_EQ(training::SpreadSamples(d, "apple", 2, "row"), (std::vector<int>{2, 4}));
  EXPECT_EQ(training::SpreadSamples(d, "apple_2", 10, "row"), (std::vector<int>{3, 4, 6}));  // All, when fewer.
  EXPECT_EQ(training::SpreadSamples(d, "pear", 1, "row"), (std::vector<int>{5}));
  EXPECT_EQ(sortcell_test::ErrorOf([&] { training::SpreadSamples(d, "banana", 3, "--row 'x:banana'"); }),
            "--row 'x:banana': no sample is labelled 'banana' (expected one of its categories or instances)");
}

TEST(ViewSheet, EachViewFillsItsTileNearestPointInFront) {
  const int tile = 40;
  // Row 0: a red square with a smaller green one nearer the camera in front of it (the green is seen
  // at its middle, though drawn first), then an empty view. Row 1: a blue square.
  perception::Cloud::Ptr both = Square(0.02, 0.5, 0, 200, 0);
  *both += *Square(0.1, 1.0, 200, 0, 0);
  const cv::Mat sheet = training::DrawViewSheet(
      {{"red behind green", {both, std::make_shared<perception::Cloud>()}}, {"blue", {Square(0.1, 1.0, 0, 0, 200)}}},
      tile);
  ASSERT_EQ(sheet.rows, 2 * tile);
  const int first = sheet.cols - 2 * tile;  // The title column's width.
  ASSERT_GT(first, 0);
  const auto at = [&](int row, int column, int x, int y) {
    return sheet.at<cv::Vec3b>(row * tile + y, first + column * tile + x);
  };
  EXPECT_EQ(at(0, 0, tile / 2, tile / 2), cv::Vec3b(0, 200, 0));  // The nearer green in front.
  EXPECT_EQ(at(0, 0, 6, 6), cv::Vec3b(0, 0, 200));                // The red square fills the tile.
  const cv::Vec3b background = sheet.at<cv::Vec3b>(0, first - 1);
  EXPECT_EQ(background, cv::Vec3b(235, 235, 235));
  EXPECT_EQ(at(0, 1, tile / 2, tile / 2), background);            // The empty view.
  EXPECT_EQ(at(1, 0, tile / 2, tile / 2), cv::Vec3b(200, 0, 0));  // Blue (BGR).
  // A 20x20 grid drawn 32 px wide: every pixel of the square covered, no gaps between the points.
  for (int y = 8; y < tile - 8; ++y) {
    for (int x = 8; x < tile - 8; ++x) EXPECT_EQ(at(1, 0, x, y), cv::Vec3b(200, 0, 0)) << x << "," << y;
  }
}

TEST(ViewSheet, NoRowsOrTinyTilesAreRefused) {
  EXPECT_EQ(sortcell_test::ErrorOf([] { training::DrawViewSheet({}, 32); }), "view sheet: no rows");
  EXPECT_EQ(sortcell_test::ErrorOf([] {
              training::DrawViewSheet({{"x", {}}}, 8);
            }),
            "view sheet: tiles of 8 px (16 or more)");
}

TEST(ViewSheet, ADegenerateViewIsADotOrNothing) {
  const int tile = 32;
  auto one = std::make_shared<perception::Cloud>();
  perception::PointT p;
  p.x = 0.1f, p.y = -0.05f, p.z = 1.0f, p.r = 200, p.g = 0, p.b = 0;
  one->push_back(p);
  // Points behind the camera, at it, not finite, or absurdly near (x/z would overflow) are left out.
  auto none = std::make_shared<perception::Cloud>();
  for (const float z : {-1.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 1e-30f}) {
    perception::PointT q = p;
    q.z = z;
    none->push_back(q);
    one->push_back(q);
  }
  const cv::Mat sheet = training::DrawViewSheet({{"degenerate", {one, none, nullptr}}}, tile);
  const int first = sheet.cols - 3 * tile;
  const cv::Vec3b background(235, 235, 235);
  // The one point: a dot in the middle of its tile, and nothing else drawn.
  EXPECT_EQ(sheet.at<cv::Vec3b>(tile / 2, first + tile / 2), cv::Vec3b(0, 0, 200));
  int drawn = 0;
  for (int y = 0; y < tile; ++y) {
    for (int x = 0; x < 3 * tile; ++x) drawn += sheet.at<cv::Vec3b>(y, first + x) != background;
  }
  EXPECT_EQ(drawn, 1);
}

TEST(ViewSheet, ARowShowsTheViewsThroughTheSensorAsModelledWhenItHasAny) {
  training::Dataset d = Labelled({"apple_1", "apple_1", "apple_1", "pear_1"});
  d.samples[0].fits_familiarity = false;  // A widened twin's view.
  EXPECT_EQ(training::SpreadSamples(d, "apple", 5, "row"), (std::vector<int>{1, 2}));
  d.samples[3].fits_familiarity = false;  // Only widened views: those, rather than none.
  EXPECT_EQ(training::SpreadSamples(d, "pear", 5, "row"), (std::vector<int>{3}));
}
