// Reading the RGB-D Object Dataset's published views (training/rgbd_objects.h): the
// back-projection, bad files named and skipped, and dataset -> train -> eval on views written in its
// format; and, where the shared sample is there, the real banana views.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "training/dataset.h"
#include "assets/image_file.h"
#include "training/rgbd_objects.h"
#include "tests/app/run_sortcell.h"

namespace fs = std::filesystem;
namespace training = sortcell::training;
namespace perception = sortcell::perception;
namespace assets = sortcell::assets;

namespace {

constexpr int kCrop = 64;
constexpr double kFocal = 570.3;

enum class Shape { kSphere, kCylinder };

// One view in the dataset's format: a sphere or an upright cylinder `radius` m across, 0.8 m away,
// seen in a 64x64 crop whose top-left is the frame's (x0, y0), 1-based.
void WriteView(const fs::path& folder, const std::string& instance, int video, int frame, Shape shape, double radius,
               const cv::Vec3b& bgr, int x0 = 289, int y0 = 209) {
  fs::create_directories(folder);
  cv::Mat colour(kCrop, kCrop, CV_8UC3, cv::Scalar(40, 40, 40)), depth(kCrop, kCrop, CV_16UC1, cv::Scalar(0)),
      mask(kCrop, kCrop, CV_8UC1, cv::Scalar(0));
  const double z0 = 0.8, pixel = z0 / kFocal;
  for (int v = 0; v < kCrop; ++v) {
    for (int u = 0; u < kCrop; ++u) {
      const double dx = (u - kCrop / 2) * pixel, dy = (v - kCrop / 2) * pixel;
      const double r2 = shape == Shape::kSphere ? dx * dx + dy * dy : dx * dx;
      if (r2 >= radius * radius || (shape == Shape::kCylinder && std::abs(dy) > 1.5 * radius)) continue;
      depth.at<uint16_t>(v, u) = static_cast<uint16_t>(std::lround(1000 * (z0 - std::sqrt(radius * radius - r2))));
      mask.at<uint8_t>(v, u) = 255;
      colour.at<cv::Vec3b>(v, u) = bgr;
    }
  }
  const std::string stem =
      (folder / (instance + "_" + std::to_string(video) + "_" + std::to_string(frame) + "_")).string();
  assets::WritePng(stem + "crop.png", colour);
  assets::WritePng(stem + "depthcrop.png", depth);
  assets::WritePng(stem + "maskcrop.png", mask);
  std::ofstream(stem + "loc.txt") << x0 << "," << y0 << "\n";
}

TEST(RgbdObjects, BackProjectsTheMaskedPixelsWithTheDatasetsCamera) {
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / "rgbd_one";
  WriteView(root / "ball" / "ball_1", "ball_1", 1, 7, Shape::kSphere, 0.03, {10, 20, 200}, 101, 51);
  const auto views = training::FindRgbdObjectsViews(root);
  ASSERT_EQ(views.size(), 1u);
  EXPECT_EQ(views[0].category, "ball");
  EXPECT_EQ(views[0].instance, "ball_1");
  EXPECT_EQ(views[0].video, 1);
  EXPECT_EQ(views[0].frame, 7);
  const perception::Cloud::Ptr cloud = training::ReadRgbdObjectsView(views[0]);
  const cv::Mat mask = assets::ReadImage(root / "ball/ball_1/ball_1_1_7_maskcrop.png", assets::PixelFormat::kGrey8);
  EXPECT_EQ(static_cast<int>(cloud->size()), cv::countNonZero(mask));
  // Every point lies on the ray of a frame pixel inside the crop (columns 100-163, rows 50-113); the
  // crop's centre pixel (32, 32) is frame pixel (132, 82), in front of the sphere's centre, 0.77 m away.
  int centre = 0;
  for (const auto& p : cloud->points) {
    const double col = p.x * kFocal / p.z + 320, row = p.y * kFocal / p.z + 240;
    EXPECT_NEAR(col, std::round(col), 1e-3);
    EXPECT_NEAR(row, std::round(row), 1e-3);
    EXPECT_GE(col, 99.5);
    EXPECT_LE(col, 163.5);
    EXPECT_GE(row, 49.5);
    EXPECT_LE(row, 113.5);
    if (std::lround(col) == 132 && std::lround(row) == 82) {
      ++centre;
      EXPECT_NEAR(p.z, 0.770, 0.0006);
      EXPECT_EQ(p.r, 200);
      EXPECT_EQ(p.b, 10);
    }
  }
  EXPECT_EQ(centre, 1);
}

TEST(RgbdObjects, MaskPixelsPastTheDepthEdgeAreLeftOut) {
  // A sphere in front of a wall 0.3 m behind it, the mask 2 px wider than the sphere (as the dataset's
  // masks reach past depth edges): the wall's pixels and the mixed ones at the rim are not the object.
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / "rgbd_edge";
  WriteView(root / "ball" / "ball_1", "ball_1", 1, 1, Shape::kSphere, 0.03, {10, 20, 200});
  const std::string stem = (root / "ball/ball_1/ball_1_1_1_").string();
  cv::Mat depth = assets::ReadImage(stem + "depthcrop.png", assets::PixelFormat::kGrey16);
  cv::Mat mask = assets::ReadImage(stem + "maskcrop.png", assets::PixelFormat::kGrey8);
  const int sphere = cv::countNonZero(mask);
  depth.setTo(1100, depth == 0);
  cv::dilate(mask, mask, cv::Mat(), cv::Point(-1, -1), 2);
  assets::WritePng(stem + "depthcrop.png", depth);
  assets::WritePng(stem + "maskcrop.png", mask);
  const perception::Cloud::Ptr cloud = training::ReadRgbdObjectsView(training::FindRgbdObjectsViews(root).at(0));
  for (const auto& p : cloud->points) EXPECT_LT(p.z, 0.80) << "a wall point at " << p.z;
  EXPECT_GT(static_cast<int>(cloud->size()), sphere * 8 / 10);  // The rim's mixed pixels only are lost.
  EXPECT_LT(static_cast<int>(cloud->size()), sphere);
}

TEST(RgbdObjects, ATablePatchTheMaskCoversBehindTheObjectIsLeftOut) {
  // The same sphere before a table only 8 cm behind it (nearer than from_median_m), the mask 5 px wider
  // than the sphere: past the rim's mixed pixels lies a ring of table, cut off from the sphere.
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / "rgbd_patch";
  WriteView(root / "ball" / "ball_1", "ball_1", 1, 1, Shape::kSphere, 0.03, {10, 20, 200});
  const std::string stem = (root / "ball/ball_1/ball_1_1_1_").string();
  cv::Mat depth = assets::ReadImage(stem + "depthcrop.png", assets::PixelFormat::kGrey16);
  cv::Mat mask = assets::ReadImage(stem + "maskcrop.png", assets::PixelFormat::kGrey8);
  const int sphere = cv::countNonZero(mask);
  depth.setTo(880, depth == 0);
  cv::dilate(mask, mask, cv::Mat(), cv::Point(-1, -1), 5);
  assets::WritePng(stem + "depthcrop.png", depth);
  assets::WritePng(stem + "maskcrop.png", mask);
  const perception::Cloud::Ptr cloud = training::ReadRgbdObjectsView(training::FindRgbdObjectsViews(root).at(0));
  for (const auto& p : cloud->points) EXPECT_LT(p.z, 0.80) << "a table point at " << p.z;
  EXPECT_GT(static_cast<int>(cloud->size()), sphere * 8 / 10);
}

TEST(RgbdObjects, BadFilesAreNamed) {
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / "rgbd_bad";
  const fs::path folder = root / "cup" / "cup_1";
  WriteView(folder, "cup_1", 1, 1, Shape::kCylinder, 0.03, {0, 200, 0});
  const auto view = training::FindRgbdObjectsViews(root).at(0);
  const auto error = [&] {
    try {
      training::ReadRgbdObjectsView(view);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::ofstream(folder / "cup_1_1_1_loc.txt") << "x=3";
  EXPECT_NE(error().find("cup_1_1_1_loc.txt': expected \"X,Y\""), std::string::npos) << error();
  std::ofstream(folder / "cup_1_1_1_loc.txt") << "600,10";
  EXPECT_NE(error().find("does not fit the 640x480 frame"), std::string::npos) << error();
  assets::WritePng((folder / "cup_1_1_1_maskcrop.png"), cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)));
  EXPECT_NE(error().find("cup_1_1_1_maskcrop.png': 10x10, but the colour crop is 64x64"), std::string::npos) << error();
  fs::remove(folder / "cup_1_1_1_depthcrop.png");
  EXPECT_NE(error().find("cup_1_1_1_depthcrop.png': missing"), std::string::npos) << error();
  std::ofstream(folder / "cup_1_1_1_depthcrop.png") << "not a png";
  EXPECT_NE(error().find("not a readable image"), std::string::npos) << error();
  EXPECT_THROW(training::FindRgbdObjectsViews(root / "nowhere"), std::invalid_argument);
}

// Two categories, `instances` each, in the dataset's layout; one view damaged.
fs::path WriteSmallDataset(const std::string& name, int instances = 2) {
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / name;
  for (int instance = 1; instance <= instances; ++instance) {
    for (int frame = 1; frame <= 8; ++frame) {
      const double scale = 1 + 0.1 * instance + 0.01 * frame;
      const std::string ball = "ball_" + std::to_string(instance), can = "can_" + std::to_string(instance);
      WriteView(root / "ball" / ball, ball, 1, frame, Shape::kSphere, 0.03 * scale, {20, 30, 190});
      WriteView(root / "can" / can, can, 1, frame, Shape::kCylinder, 0.025 * scale, {30, 180, 40});
    }
  }
  fs::remove(root / "can" / "can_2" / "can_2_1_8_maskcrop.png");
  return root;
}

// A dataset root holding only the shared real banana (the shared folder also holds real apples and
// balls, categories the models here know), linked into this test's folder; empty where ../shared
// is not beside this checkout.
fs::path RealBananaOnly(const std::string& name) {
  const fs::path banana = fs::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real" / "rgbd-object" / "banana";
  if (!fs::is_directory(banana)) return {};
  const fs::path root = fs::path(sortcell_test::TestTempDir()) / name;
  // File by file: the reader walks real folders, not links to them.
  for (const auto& instance : fs::directory_iterator(banana)) {
    const fs::path folder = root / "banana" / instance.path().filename();
    fs::create_directories(folder);
    for (const auto& file : fs::directory_iterator(instance.path())) {
      fs::create_symlink(fs::absolute(file.path()), folder / file.path().filename());
    }
  }
  return root;
}

TEST(RgbdObjects, ImportTrainAndEvalRunOnTheDatasetsFormat) {
  const fs::path root = WriteSmallDataset("rgbd_small");
  const fs::path out = fs::path(sortcell_test::TestTempDir()) / "rgbd_small_out";
  const auto r =
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + root.string() + " --out " + (out / "data").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const training::Dataset d = training::LoadDataset(out / "data");
  EXPECT_EQ(d.samples.size(), 31u);
  ASSERT_EQ(d.capture["skipped"].size(), 1u);
  EXPECT_NE(d.capture["skipped"][0]["reason"].get<std::string>().find("can_2_1_8_maskcrop.png': missing"),
            std::string::npos);
  EXPECT_EQ(d.Labels(perception::LabelKind::kCategory), (std::vector<std::string>{"ball", "can"}));
  EXPECT_EQ(d.samples[0].source, "rgbd-objects");
  EXPECT_EQ(d.samples[0].elevation_deg, 30);
  const fs::path model = out / "model.json";
  ASSERT_EQ(sortcell_test::RunSortcell("train --dataset " + (out / "data").string() +
                                       " --descriptor color-cvfh-norm --out " + model.string())
                .exit_code,
            0);
  const auto eval = sortcell_test::RunSortcell("eval --dataset " + (out / "data").string() + " --model " +
                                               model.string() + " --out " + (out / "eval").string());
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  const nlohmann::json results = nlohmann::json::parse(std::ifstream(out / "eval" / "results.json"));
  EXPECT_EQ(results["test_samples"], 31);
  // A red ball and a green can, seen in training: the model tells them apart.
  EXPECT_GE(results["accuracy"].get<double>(), 0.95);
  EXPECT_FALSE(results.contains("out_of_set"));
  // Instance by instance: each known, its share called right, its confidences binned by tenths.
  const auto& can2 = results["by_instance"]["can_2"];
  EXPECT_EQ(can2["category"], "can");
  EXPECT_TRUE(can2["known"].get<bool>());
  EXPECT_EQ(can2["samples"], 7);  // Its eighth view has no mask.
  EXPECT_GE(can2["correct_share"].get<double>(), 0.95);
  int binned = 0;
  for (int n : can2["histogram"]) binned += n;
  EXPECT_EQ(binned, 7);
  EXPECT_NE(eval.out.find("can_2 (can): "), std::string::npos) << eval.out;

  // The real banana (where ../shared is beside the checkout), a category this model does not know:
  // eval reports what it was called and how confidently, not a score.
  const fs::path banana = RealBananaOnly("rgbd_banana_unknown");
  if (banana.empty()) GTEST_SKIP() << "no ../shared/real/rgbd-object/banana beside this checkout";
  ASSERT_EQ(sortcell_test::RunSortcell("dataset --from-rgbd-objects " + banana.string() + " --out " +
                                       (out / "banana").string())
                .exit_code,
            0);
  const auto unknown = sortcell_test::RunSortcell("eval --dataset " + (out / "banana").string() + " --model " +
                                                  model.string() + " --out " + (out / "eval_banana").string());
  ASSERT_EQ(unknown.exit_code, 0) << unknown.err;
  EXPECT_NE(unknown.out.find("samples of categories it does not know"), std::string::npos) << unknown.out;
  const nlohmann::json b = nlohmann::json::parse(std::ifstream(out / "eval_banana" / "results.json"));
  const auto& report = b["out_of_set"]["banana"];
  EXPECT_EQ(report["samples"].get<int>(), static_cast<int>(training::LoadDataset(out / "banana").samples.size()));
  int called = 0;
  for (const auto& [name, n] : report["called"].items()) {
    EXPECT_TRUE(name == "ball" || name == "can") << name;
    called += n.get<int>();
  }
  EXPECT_EQ(called, report["samples"].get<int>());
  EXPECT_GE(report["confidence"]["max"].get<double>(), report["confidence"]["median"].get<double>());
  EXPECT_LE(report["confidence"]["max"].get<double>(), 1.0);
  EXPECT_FALSE(b.contains("accuracy"));  // Nothing of the model's classes to score.
  std::ifstream tables(out / "eval_banana" / "tables.md");
  const std::string md((std::istreambuf_iterator<char>(tables)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("| banana | "), std::string::npos) << md;
  EXPECT_NE(md.find("| banana_1 | banana (unknown) | "), std::string::npos) << md;
  EXPECT_FALSE(b["by_instance"]["banana_1"]["known"].get<bool>());
  EXPECT_TRUE(b["by_instance"]["banana_1"]["correct_share"].is_null());
}

TEST(RgbdObjects, TheCommandRefusesAMixOfSourcesAndAnEmptyFolder) {
  const fs::path empty = fs::path(sortcell_test::TestTempDir()) / "rgbd_empty";
  fs::create_directories(empty);
  const std::string out = (fs::path(sortcell_test::TestTempDir()) / "rgbd_refused").string();
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + empty.string() + " --out " + out),
      "no <instance>_<video>_<frame>_crop.png view in it");
  EXPECT_EQ(sortcell_test::RunSortcell("dataset --from-rgbd-objects " + empty.string() +
                                       " --objects scenes/objects/paper.yaml --out " + out)
                .exit_code,
            2);
  EXPECT_EQ(
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + empty.string() + " --views 5 --out " + out).exit_code,
      2);
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell("dataset --out " + out), "--from-rgbd-objects DIR");
}

TEST(RgbdObjects, ExperimentOneRunsOnAnImportedDataset) {
  const fs::path root = WriteSmallDataset("rgbd_three", 3);
  const fs::path out = fs::path(sortcell_test::TestTempDir()) / "rgbd_three_out";
  ASSERT_EQ(
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + root.string() + " --out " + (out / "data").string())
          .exit_code,
      0);
  const std::string data = " --data " + (out / "data").string();
  const auto unseen =
      sortcell_test::RunSortcell("experiment 1 --split unseen-instance" + data + " --out " + (out / "unseen").string());
  ASSERT_EQ(unseen.exit_code, 0) << unseen.err;
  const nlohmann::json results = nlohmann::json::parse(std::ifstream(out / "unseen" / "results.json"));
  EXPECT_EQ(results["trials"], 3);  // Every instance held out once.
  EXPECT_EQ(results["split_detail"].size(), 3u);
  const nlohmann::json& norm = results["descriptors"]["color-cvfh-norm"];
  ASSERT_EQ(norm["trials"].size(), 3u);
  double sum = 0;
  for (const auto& t : norm["trials"]) sum += t["macro_f1"].get<double>();
  EXPECT_NEAR(norm["macro_f1"].get<double>(), sum / 3, 1e-12);  // The mean over the trials.
  EXPECT_TRUE(norm.contains("macro_f1_std"));
  // A red ball and a green can: unseen instances of them are still told apart by colour.
  EXPECT_GE(norm["macro_f1"].get<double>(), 0.9);
  std::ifstream tables(out / "unseen" / "tables.md");
  const std::string text((std::istreambuf_iterator<char>(tables)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("| **mean ± std** |"), std::string::npos);
  EXPECT_EQ(sortcell_test::RunSortcell("experiment 1" + data + " --out " + (out / "paper").string()).exit_code, 0);
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("experiment 3" + data + " --out " + (out / "three").string()), "holds one dataset");
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("experiment 1 --trials 2" + data + " --out " + (out / "x").string()),
      "--trials: only the unseen-instance split has trials");
}

// The shared real sample's banana (100 views), where this checkout has it beside it.
TEST(RgbdObjects, ReadsTheRealSample) {
  const fs::path sample = RealBananaOnly("rgbd_banana_root");
  if (sample.empty()) GTEST_SKIP() << "no ../shared/real/rgbd-object/banana beside this checkout";
  const fs::path out = fs::path(sortcell_test::TestTempDir()) / "rgbd_banana";
  const auto r =
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + sample.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const training::Dataset d = training::LoadDataset(out);
  EXPECT_EQ(d.samples.size() + d.capture["skipped"].size(), 100u);
  EXPECT_GE(d.samples.size(), 95u);
  EXPECT_EQ(d.Labels(perception::LabelKind::kCategory), std::vector<std::string>{"banana"});
  EXPECT_EQ(d.Labels(perception::LabelKind::kInstance), std::vector<std::string>{"banana_1"});
  // About a metre from the camera, a banana's few hundred to thousands of points.
  for (const auto& s : d.samples) {
    EXPECT_GT(s.points, 300) << s.cloud;
  }
}

}  // namespace

TEST(RgbdObjects, ViewsDrawsRowsOfADatasetAndRefusesBadRows) {
  const fs::path root = WriteSmallDataset("rgbd_views");
  const fs::path out = fs::path(sortcell_test::TestTempDir()) / "rgbd_views_out";
  ASSERT_EQ(
      sortcell_test::RunSortcell("dataset --from-rgbd-objects " + root.string() + " --out " + (out / "data").string())
          .exit_code,
      0);
  const std::string data = (out / "data").string(), png = (out / "sheet" / "views.png").string();
  const auto r = sortcell_test::RunSortcell("views --row " + data + ":ball --row " + data +
                                            ":can_2 --per-row 3 --tile 32 --out " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat sheet = assets::ReadImage(png, assets::PixelFormat::kBgr8);
  ASSERT_EQ(sheet.rows, 2 * 32);
  const int first = sheet.cols - 3 * 32;  // After the titles: the first view of each row.
  EXPECT_EQ(sheet.at<cv::Vec3b>(16, first + 16), cv::Vec3b(20, 30, 190));  // The red ball.
  EXPECT_EQ(sheet.at<cv::Vec3b>(48, first + 16), cv::Vec3b(30, 180, 40));  // The green can.
  const std::string views = "views --per-row 3 --out " + png + " --row ";
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell(views + data + ":banana"),
                                    "no sample is labelled 'banana'");
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell(views + data), "expected DATASET:LABEL");
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell(views + "/nonexistent:ball"), "/nonexistent");
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell(views + data + ":ball --tile 8"), "--tile");
  // A cloud the manifest names that is gone: the row and the file named.
  const training::Dataset d = training::LoadDataset(data);
  const fs::path gone = fs::path(data) / d.samples.front().cloud;
  fs::remove(gone);
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("views --per-row 40 --out " + png + " --row " + data + ":ball"),
      "--row '" + data + ":ball': PCD '" + gone.string() + "'");
}
