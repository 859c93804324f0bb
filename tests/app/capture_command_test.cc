// `sortcell capture` end to end: the files it writes and their formats.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "assets/image_file.h"
#include "tests/app/run_sortcell.h"
#include "source_tree.h"

namespace fs = std::filesystem;
namespace assets = sortcell::assets;

namespace {

using sortcell_test::kCell;
using sortcell_test::Result;
using sortcell_test::RunSortcell;
using sortcell_test::TestTempDir;

TEST(CliCapture, WritesEveryFile) {
  const fs::path out = fs::path(TestTempDir()) / "cli_capture";
  const Result r = RunSortcell("capture --scene " + kCell + " --seed 5 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"rgb.png", "depth.png", "cloud.pcd", "labels.png", "labels.json", "camera.json", "run.json"}) {
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  }
  const cv::Mat depth = assets::ReadImage(out / "depth.png", assets::PixelFormat::kGrey16);
  EXPECT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(depth.cols, 640);
  double lo, hi;
  cv::minMaxLoc(depth, &lo, &hi);
  EXPECT_EQ(lo, 0);    // Some invalid pixels (shadows, edges).
  EXPECT_GT(hi, 900);  // Millimetres: the table is about a metre away.
  EXPECT_LT(hi, 4001);
  const cv::Mat rgb = assets::ReadImage(out / "rgb.png", assets::PixelFormat::kBgr8);
  EXPECT_EQ(rgb.rows, 480);
  const cv::Mat labels = assets::ReadImage(out / "labels.png", assets::PixelFormat::kGrey16);
  EXPECT_EQ(labels.type(), CV_16UC1);

  std::ifstream pcd(out / "cloud.pcd");
  std::string line, data_line;
  while (std::getline(pcd, line)) {
    if (line.rfind("DATA", 0) == 0) {
      data_line = line;
      break;
    }
  }
  EXPECT_EQ(data_line, "DATA binary_compressed");
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile((out / "cloud.pcd").string(), cloud), 0);
  EXPECT_EQ(cloud.width, 640u);
  EXPECT_EQ(cloud.height, 480u);
  EXPECT_FALSE(cloud.is_dense);

  const auto camera = nlohmann::json::parse(std::ifstream(out / "camera.json"));
  EXPECT_NEAR(camera["fx"].get<double>(), 525.0, 0.5);
  EXPECT_EQ(camera["X_WC"].size(), 4u);
  EXPECT_NEAR(camera["X_WC"][0][3].get<double>(), 1.25, 1e-9);
  const auto run = nlohmann::json::parse(std::ifstream(out / "run.json"));
  EXPECT_EQ(run["seed"].get<uint64_t>(), 5u);
  EXPECT_FALSE(run["git_revision"].get<std::string>().empty());
  EXPECT_EQ(run["command"], "capture");
  const auto labels_json = nlohmann::json::parse(std::ifstream(out / "labels.json"));
  EXPECT_EQ(labels_json["labels"]["1"], "bottle1");
  EXPECT_GT(labels_json["pixels"]["ball"].get<int>(), 500);
}

}  // namespace
