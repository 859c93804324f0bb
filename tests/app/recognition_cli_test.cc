// Bad input to segment (including a cloud without a table or without depth), dataset, train, eval
// and experiment: one line naming the culprit, exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "run_sortcell.h"

namespace {

using sortcell_test::ExpectOneLineError;
using sortcell_test::RunSortcell;

std::string Dir() {
  const std::string d = sortcell_test::TestTempDir() + "recognition_cli";
  std::filesystem::create_directories(d);
  return d;
}

TEST(RecognitionCli, SegmentRejectsMissingAndNonPcdFiles) {
  ExpectOneLineError(RunSortcell("segment --pcd /nonexistent/cloud.pcd --out " + Dir() + "/s"),
                     "PCD '/nonexistent/cloud.pcd': no such file");
  std::ofstream(Dir() + "/junk.pcd") << "not a cloud";
  ExpectOneLineError(RunSortcell("segment --pcd " + Dir() + "/junk.pcd --out " + Dir() + "/s"),
                     "not a readable PCD file");
  std::ofstream(Dir() + "/camera.json") << "{\"X_WC\": [[1, 0, 0]]}";
  std::ofstream(Dir() + "/flat.pcd") << "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
                                        "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n0 0 1 0\n";
  // An unorganized cloud segments (below), but cannot be background-subtracted pixel by pixel.
  ExpectOneLineError(
      RunSortcell("segment --pcd " + Dir() + "/flat.pcd --background " + Dir() + "/flat.pcd --out " + Dir() + "/s"),
      "--background: PCD '" + Dir() + "/flat.pcd' is unorganized (height 1)");
  ExpectOneLineError(RunSortcell("segment --pcd " + Dir() + "/flat.pcd --clustering fancy --out " + Dir() + "/s"),
                     "--clustering");
}

TEST(RecognitionCli, SegmentsAnUnorganizedRealCaptureWithoutAnOverlay) {
  const std::filesystem::path real =
      std::filesystem::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real" / "mosd-learn" / "learn0.pcd";
  if (!std::filesystem::exists(real)) GTEST_SKIP() << "no " << real << " beside this checkout";
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(real.string(), cloud), 0);
  pcl::PointCloud<pcl::PointXYZRGB> row;
  for (const auto& p : cloud) {
    if (std::isfinite(p.z)) row.push_back(p);  // As a scanner or a merged view delivers it: valid points only.
  }
  ASSERT_EQ(row.height, 1u);
  pcl::io::savePCDFileBinaryCompressed(Dir() + "/row.pcd", row);
  for (const std::string clustering : {"euclidean", "convex", ""}) {  // "": the default, convex.
    const std::string out = Dir() + "/row_" + clustering;
    const auto r = RunSortcell("segment --pcd " + Dir() + "/row.pcd" +
                               (clustering.empty() ? "" : " --clustering " + clustering) + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto run = nlohmann::json::parse(std::ifstream(out + "/run.json"));
    EXPECT_EQ(run.at("clustering"), clustering.empty() ? "convex" : clustering);
    EXPECT_NE(r.out.find(": 2 objects."), std::string::npos) << r.out;  // Two boxes, side by side.
    EXPECT_NE(r.out.find("no overlay.png"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(out + "/overlay.png"));
    EXPECT_TRUE(std::filesystem::exists(out + "/segment_01.pcd"));
  }
}

TEST(RecognitionCli, SegmentSaysWhenACloudHasNoTableOrNoDepth) {
  const std::string header =
      "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
      "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n";
  std::ofstream(Dir() + "/four.pcd") << header << "0 0 1 0\n0.01 0 1 0\n0 0.01 1 0\n0.01 0.01 1 0\n";
  ExpectOneLineError(
      RunSortcell("segment --pcd " + Dir() + "/four.pcd --out " + Dir() + "/s"),
      "PCD '" + Dir() + "/four.pcd': segmentation: no supporting plane found (0 sampled inliers of 1, need 200)");
  std::ofstream(Dir() + "/nan.pcd") << header << "nan nan nan 0\nnan nan nan 0\nnan nan nan 0\nnan nan nan 0\n";
  ExpectOneLineError(RunSortcell("segment --pcd " + Dir() + "/nan.pcd --out " + Dir() + "/s"),
                     "PCD '" + Dir() + "/nan.pcd': segmentation: the cloud has no valid point (all NaN)");
}

TEST(RecognitionCli, TrainAndEvalRejectUnknownDescriptorMissingDatasetAndBadModel) {
  ExpectOneLineError(RunSortcell("train --dataset " + Dir() + " --descriptor vfh --out " + Dir() + "/m.json"),
                     "unknown descriptor 'vfh' (expected cvfh, color-cvfh or color-cvfh-norm)");
  ExpectOneLineError(RunSortcell("train --dataset /nonexistent --descriptor cvfh --out " + Dir() + "/m.json"),
                     "dataset '/nonexistent': no manifest.json");
  std::ofstream(Dir() + "/bad.model.json") << "{\"format\": \"something else\"}";
  ExpectOneLineError(
      RunSortcell("eval --dataset " + Dir() + " --model " + Dir() + "/bad.model.json --out " + Dir() + "/e"),
      "not a SortCell recognition model");
  ExpectOneLineError(
      RunSortcell("train --dataset " + Dir() + " --descriptor cvfh --label colour --out " + Dir() + "/m"),
      "--label: unknown label kind 'colour'");
}

TEST(RecognitionCli, TrainFromASetRejectsAMissingSetAndRecipeOptions) {
  ExpectOneLineError(RunSortcell("train --objects " + Dir() + "/none.yaml --out " + Dir() + "/m.json"), "none.yaml");
  ExpectOneLineError(RunSortcell("train --out " + Dir() + "/m.json"), "give --dataset DIR or --objects SET.yaml");
  // The recipe is the default model's: its descriptor and labels are not the user's to change here.
  ExpectOneLineError(
      RunSortcell("train --objects " + Dir() + "/none.yaml --descriptor cvfh --out " + Dir() + "/m.json"),
      "--descriptor");
  ExpectOneLineError(RunSortcell("train --objects a.yaml --dataset " + Dir() + " --out " + Dir() + "/m.json"),
                     "--dataset");
  ExpectOneLineError(RunSortcell("train --dataset " + Dir() + " --if-stale --out " + Dir() + "/m.json"), "--if-stale");
  ExpectOneLineError(RunSortcell("dataset --objects a.yaml --classifier-only --out " + Dir() + "/d"),
                     "--classifier-only");
}

TEST(RecognitionCli, ExperimentAndDatasetRejectBadValues) {
  ExpectOneLineError(RunSortcell("experiment 4 --out " + Dir() + "/x"), "experiment");
  ExpectOneLineError(RunSortcell("experiment 2 --split unseen-instance --out " + Dir() + "/x"),
                     "--split: experiment 2 has only the paper split");
  ExpectOneLineError(RunSortcell("experiment 1 --split random --out " + Dir() + "/x"), "unknown split 'random'");
  ExpectOneLineError(RunSortcell("dataset --objects /nonexistent.yaml --out " + Dir() + "/d"), "/nonexistent.yaml");
  ExpectOneLineError(RunSortcell("dataset --objects x.yaml --views 2 --out " + Dir() + "/d"), "--views");
}

}  // namespace
