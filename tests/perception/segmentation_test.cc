// Segmentation on synthetic organized clouds: a table plane with objects, and bad input.
#include "perception/segmentation.h"

#include <gtest/gtest.h>

#include "error_of.h"

#include <pcl/io/pcd_io.h>
#include <opencv2/core/types.hpp>

#include <filesystem>
#include <fstream>
#include <limits>

#include "perception/pcd_io.h"
#include "temp_dir.h"
#include "test_clouds.h"

namespace sortcell::perception {
namespace {

// A 160x120 camera (f = 130 px) looking straight down from 1 m at a table (z_C = 1), with boxes of
// height h standing on it at the given pixel rectangles. Camera = world rotated: X_WC flips y and z.
struct Scene {
  Cloud cloud;
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
};

Scene TableWithBoxes(const std::vector<cv::Rect>& boxes, double h) {
  Scene s;
  s.cloud = Cloud(160, 120);
  const double f = 130;
  for (int v = 0; v < 120; ++v) {
    for (int u = 0; u < 160; ++u) {
      double z = 1.0;
      for (const auto& b : boxes) {
        if (b.contains(cv::Point(u, v))) z = 1.0 - h;
      }
      s.cloud.at(u, v) = sortcell_test::Point((u - 79.5) * z / f, (v - 59.5) * z / f, z, 180, 160, 120);
    }
  }
  // World: table top z = 0, camera 1 m above it looking down (optical z = -world z).
  s.X_WC.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  s.X_WC.translation() = Eigen::Vector3d(0.5, 0, 1.0);
  return s;
}

SegmentationParams OpenBox() {
  SegmentationParams p;
  p.workspace_min_W = Eigen::Vector3d(-1, -1, -0.05);
  p.workspace_max_W = Eigen::Vector3d(2, 1, 0.5);
  return p;
}

using sortcell_test::ErrorOf;

TEST(Segmentation, FindsEachObjectOnTheTableWithAndWithoutPose) {
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25), cv::Rect(100, 60, 30, 20)}, 0.08);
  for (const bool with_pose : {true, false}) {
    const auto pose = with_pose ? std::optional<Eigen::Isometry3d>(s.X_WC) : std::nullopt;
    const SegmentationResult r = SegmentObjects(s.cloud, pose, nullptr, OpenBox());
    ASSERT_EQ(r.segments.size(), 2u) << (with_pose ? "with pose" : "camera frame");
    EXPECT_EQ(r.world_frame, with_pose);
    // Largest first: the 30x20 box (600 px) then 25x25 (625 px) ... by voxels; check pixels instead.
    size_t pixels = r.segments[0].indices.size() + r.segments[1].indices.size();
    EXPECT_EQ(pixels, 25u * 25 + 30 * 20);
    for (const auto& seg : r.segments) {
      EXPECT_EQ(seg.cloud_C->size(), seg.indices.size());
      if (with_pose) {
        EXPECT_NEAR(seg.centroid.z(), 0.08, 0.002) << "box tops, 8 cm above the table";
      } else {
        EXPECT_NEAR(seg.centroid.z(), 0.92, 0.002) << "camera frame: 0.92 m away";
      }
    }
    EXPECT_NEAR(std::abs(r.plane_C[2]), 1.0, 1e-3);
    EXPECT_GT(r.plane_C[3], 0) << "the camera is on the plane's positive side";
  }
}

TEST(Segmentation, BackgroundSubtractionRemovesWhatTheEmptySceneHas) {
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25), cv::Rect(100, 60, 30, 20)}, 0.08);
  const Scene background = TableWithBoxes({cv::Rect(100, 60, 30, 20)}, 0.08);  // That box is fixture.
  const SegmentationResult r = SegmentObjects(s.cloud, s.X_WC, &background.cloud, OpenBox());
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_EQ(r.segments[0].indices.size(), 25u * 25);
}

TEST(Segmentation, WorkspaceBoxCropsOutsideObjects) {
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25), cv::Rect(100, 60, 30, 20)}, 0.08);
  SegmentationParams p = OpenBox();
  p.workspace_min_W.x() = 0.5;  // Keeps the right half of the image only.
  const SegmentationResult r = SegmentObjects(s.cloud, s.X_WC, nullptr, p);
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_GT(r.segments[0].centroid.x(), 0.5);
}

TEST(Segmentation, RejectsMisuseEmptyUnorganizedWithBackgroundAndBackgroundOfAnotherSize) {
  Cloud empty;
  EXPECT_EQ(ErrorOf([&] { SegmentObjects(empty, std::nullopt, nullptr); }), "segmentation: the cloud is empty");
  Cloud flat = TableWithBoxes({}, 0).cloud;
  const Cloud background = flat;
  flat.height = 1;
  flat.width = static_cast<uint32_t>(flat.size());
  EXPECT_NE(ErrorOf([&] { SegmentObjects(flat, std::nullopt, &background); }).find("needs an organized cloud"),
            std::string::npos);
  Cloud wrong = flat;
  wrong.width = 7;
  EXPECT_NE(ErrorOf([&] { SegmentObjects(wrong, std::nullopt, nullptr); }).find("not its 7x1"), std::string::npos);
  const Scene s = TableWithBoxes({}, 0);
  Cloud small(10, 10);
  EXPECT_NE(ErrorOf([&] { SegmentObjects(s.cloud, s.X_WC, &small); }).find("background cloud is 10x10"),
            std::string::npos);
}

TEST(Segmentation, AnUnorganizedCloudSegmentsLikeTheOrganizedOne) {
  // The same points in a row (height 1), without and with a pose: the same objects, point for point.
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 30, 30), cv::Rect(100, 60, 30, 40)}, 0.1);
  Cloud row = s.cloud;
  row.height = 1;
  row.width = static_cast<uint32_t>(row.size());
  for (const auto& pose : {std::optional<Eigen::Isometry3d>(), std::optional(s.X_WC)}) {
    const SegmentationResult organized = SegmentObjects(s.cloud, pose, nullptr, OpenBox());
    const SegmentationResult unorganized = SegmentObjects(row, pose, nullptr, OpenBox());
    ASSERT_EQ(organized.segments.size(), 2u);
    ASSERT_EQ(unorganized.segments.size(), 2u);
    for (size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(unorganized.segments[k].indices, organized.segments[k].indices);  // Point index = pixel index.
      EXPECT_NEAR((unorganized.segments[k].centroid - organized.segments[k].centroid).norm(), 0.0, 2e-3);
    }
  }
}

TEST(Segmentation, NoValidPointIsAStatusNotAnError) {
  Cloud nan(40, 30);
  for (auto& p : nan) p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  const SegmentationResult r = SegmentObjects(nan, std::nullopt, nullptr);
  EXPECT_EQ(r.status, SegmentationStatus::kNoValidPoints);
  EXPECT_EQ(r.detail, "segmentation: the cloud has no valid point (all NaN)");
  EXPECT_TRUE(r.segments.empty());

  // Valid points, all outside the workspace box: nothing left to segment.
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25)}, 0.08);
  SegmentationParams p = OpenBox();
  p.workspace_min_W.z() = 1.5;
  p.workspace_max_W.z() = 2.0;
  const SegmentationResult outside = SegmentObjects(s.cloud, s.X_WC, nullptr, p);
  EXPECT_EQ(outside.status, SegmentationStatus::kNoValidPoints);
  EXPECT_NE(outside.detail.find("no valid point inside the workspace box"), std::string::npos) << outside.detail;
  EXPECT_TRUE(outside.segments.empty());
}

TEST(Segmentation, NoSupportingPlaneIsAStatusNotAnError) {
  Cloud sparse(40, 30);  // Few valid points, no plane.
  for (auto& p : sparse) p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  sparse.at(3, 3) = sortcell_test::Point(0, 0, 1, 1, 1, 1);
  const SegmentationResult r = SegmentObjects(sparse, std::nullopt, nullptr);
  EXPECT_EQ(r.status, SegmentationStatus::kNoPlane);
  EXPECT_EQ(r.detail,
            "segmentation: no supporting plane found (0 sampled inliers of 1, need 200): expected "
            "objects standing on a table or floor");
  EXPECT_TRUE(r.segments.empty());

  // The one valid point is the empty cell's depth, off the plane's sampling grid (neither its row 5 nor its
  // column 4 a multiple of the stride, 3): nothing samples it and nothing keeps it, yet it is inside the region:
  // no plane, not "no valid point". With a pose, the same inside the workspace box, and "no valid point" outside.
  Cloud lone(40, 30);
  for (auto& p : lone) p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  lone.at(4, 5) = sortcell_test::Point(0, 0, 1, 1, 1, 1);
  SegmentationParams around_it = OpenBox();
  around_it.workspace_max_W.z() = 1.5;  // The point is at world z = 1 with the identity pose.
  for (const auto& pose : {std::optional<Eigen::Isometry3d>(), std::optional(Eigen::Isometry3d::Identity())}) {
    const SegmentationResult background_only = SegmentObjects(lone, pose, &lone, around_it);
    EXPECT_EQ(background_only.status, SegmentationStatus::kNoPlane);
    EXPECT_EQ(background_only.detail,
              "segmentation: no supporting plane found (0 sampled inliers of 0, need 200): expected "
              "objects standing on a table or floor");
  }
  const SegmentationResult outside_box = SegmentObjects(lone, Eigen::Isometry3d::Identity(), &lone, OpenBox());
  EXPECT_EQ(outside_box.status, SegmentationStatus::kNoValidPoints);
  EXPECT_NE(outside_box.detail.find("no valid point inside the workspace box"), std::string::npos);

  // With a pose the plane must be horizontal in the world: a wall-like view has none.
  const Scene s = TableWithBoxes({}, 0);
  Eigen::Isometry3d X_WC_sideways = s.X_WC;
  X_WC_sideways.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  SegmentationParams wide = OpenBox();
  wide.workspace_min_W = Eigen::Vector3d(-5, -5, -5);
  wide.workspace_max_W = Eigen::Vector3d(5, 5, 5);
  const SegmentationResult tilted = SegmentObjects(s.cloud, X_WC_sideways, nullptr, wide);
  EXPECT_EQ(tilted.status, SegmentationStatus::kNoPlane);
  EXPECT_NE(tilted.detail.find("no supporting plane found"), std::string::npos) << tilted.detail;
}

TEST(Segmentation, OkHasNoDetailAndStatusesHaveTheirSpellings) {
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25)}, 0.08);
  const SegmentationResult r = SegmentObjects(s.cloud, s.X_WC, nullptr, OpenBox());
  EXPECT_EQ(r.status, SegmentationStatus::kOk);
  EXPECT_TRUE(r.detail.empty());
  EXPECT_STREQ(ToString(SegmentationStatus::kOk), "ok");
  EXPECT_STREQ(ToString(SegmentationStatus::kNoValidPoints), "no_valid_points");
  EXPECT_STREQ(ToString(SegmentationStatus::kNoPlane), "no_plane");
}

TEST(PcdIo, MosdLabelsBecomeObjectIdsAndACloudWithoutLabelsIsNamed) {
  pcl::PointCloud<pcl::PointXYZRGBL> labelled(4, 1);
  const uint32_t labels[] = {0, 3, 21, 37};  // No depth, table, object 2, object 3.
  for (int i = 0; i < 4; ++i) labelled[i].label = labels[i];
  const sortcell_test::TempDir temp("mosd_ids");
  pcl::io::savePCDFileBinaryCompressed(temp.str() + "/labelled.pcd", labelled);
  EXPECT_EQ(LoadMosdObjectIds(temp.str() + "/labelled.pcd"), (std::vector<int>{0, 0, 2, 3}));
  pcl::PointCloud<pcl::PointXYZRGB> plain(4, 1);
  pcl::io::savePCDFileBinaryCompressed(temp.str() + "/plain.pcd", plain);
  EXPECT_EQ(ErrorOf([&] { LoadMosdObjectIds(temp.str() + "/plain.pcd"); }),
            "PCD '" + temp.str() + "/plain.pcd': no 'label' field");
}

TEST(PcdIo, ReadsAnOpenNiStyleXyzrgbaCaptureAndRejectsBadFiles) {
  const Scene s = TableWithBoxes({cv::Rect(20, 20, 25, 25)}, 0.08);
  pcl::PointCloud<pcl::PointXYZRGBA> grabber(160, 120);
  for (size_t i = 0; i < s.cloud.size(); ++i) {
    grabber[i].getVector3fMap() = s.cloud[i].getVector3fMap();
    grabber[i].r = 10;
    grabber[i].g = 20;
    grabber[i].b = 30;
    grabber[i].a = 255;
  }
  const sortcell_test::TempDir temp("pcd_io");
  const std::string dir = temp.str();
  pcl::io::savePCDFileBinaryCompressed(dir + "/grabber.pcd", grabber);
  const Cloud::Ptr loaded = LoadCloud(dir + "/grabber.pcd", true);
  ASSERT_EQ(loaded->width, 160u);
  ASSERT_EQ(loaded->height, 120u);
  EXPECT_EQ(loaded->at(5, 5).g, 20);
  EXPECT_EQ(SegmentObjects(*loaded, std::nullopt, nullptr, OpenBox()).segments.size(), 1u);

  pcl::PointCloud<pcl::PointXYZ> xyz(160, 120);
  pcl::io::savePCDFileBinary(dir + "/xyz.pcd", xyz);
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/xyz.pcd", true); }),
            "PCD '" + dir + "/xyz.pcd': missing field 'rgb' (or 'rgba'): colour is needed");
  Cloud unorganized = s.cloud;
  unorganized.height = 1;
  unorganized.width = static_cast<uint32_t>(unorganized.size());
  pcl::io::savePCDFileBinary(dir + "/flat.pcd", unorganized);
  EXPECT_NE(ErrorOf([&] { LoadCloud(dir + "/flat.pcd", true); }).find("not organized (19200x1)"), std::string::npos);
  std::ofstream(dir + "/junk.pcd") << "hello";
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/junk.pcd", true); }),
            "PCD '" + dir + "/junk.pcd': not a readable PCD file (no FIELDS or no points in the header)");
  std::ofstream(dir + "/truncated.pcd") << "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
                                           "WIDTH 640\nHEIGHT 480\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 307200\n"
                                           "DATA binary_compressed\nabc";
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/truncated.pcd", true); }),
            "PCD '" + dir +
                "/truncated.pcd': not a readable PCD file (the header claims more points than the file "
                "holds)");
  // Found by fuzzing (fuzz/regressions/pcd): PCL 1.13 allocates a compressed block's stored size
  // unchecked, and reads a field by its name whatever its size.
  std::ofstream(dir + "/huge_block.pcd") << "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
                                            "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA binary_compressed\n"
                                         << std::string("\x10\x00\x00\x00\xff\xff\xff\xff", 8) << std::string(16, '\0');
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/huge_block.pcd", false); }),
            "PCD '" + dir +
                "/huge_block.pcd': not a readable PCD file (damaged compressed data: sizes do not match the "
                "header)");
  std::ofstream(dir + "/short_rgb.pcd") << "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 1\nTYPE F F F U\nCOUNT 1 1 1 1\n"
                                           "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n0.1 0.2 0.3 7\n";
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/short_rgb.pcd", false); }),
            "PCD '" + dir + "/short_rgb.pcd': field 'rgb': expected one 4-byte packed colour per point");
  std::ofstream(dir + "/empty.pcd");
  EXPECT_EQ(ErrorOf([&] { LoadMosdObjectIds(dir + "/empty.pcd"); }),
            "PCD '" + dir + "/empty.pcd': not a readable PCD file (no FIELDS or no points in the header)");
  EXPECT_EQ(ErrorOf([&] { LoadCloud(dir + "/none.pcd", true); }), "PCD '" + dir + "/none.pcd': no such file");
}

}  // namespace
}  // namespace sortcell::perception
