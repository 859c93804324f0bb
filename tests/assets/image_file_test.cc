// Image files without OpenCV's imgcodecs: PNGs written and read back exactly (colour, grey, 16-bit
// depth), JPEG textures decoded, anything else read as an empty image for the caller to refuse.
#include "assets/image_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "assets/user_objects.h"
#include "temp_dir.h"

namespace sortcell::assets {
namespace {

cv::Mat Gradient(int type) {
  cv::Mat image(7, 9, type);
  cv::randu(image, 0, type == CV_16UC1 ? 4000 : 256);
  return image;
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(ImageFile, PngsComeBackAsWritten) {
  sortcell_test::TempDir dir;
  const std::pair<int, PixelFormat> kinds[] = {
      {CV_8UC3, PixelFormat::kBgr8}, {CV_8UC1, PixelFormat::kGrey8}, {CV_16UC1, PixelFormat::kGrey16}};
  for (const auto& [type, format] : kinds) {
    const cv::Mat image = Gradient(type);
    const auto file = dir.path() / "image.png";
    ASSERT_TRUE(WritePng(file, image));
    EXPECT_TRUE(Same(ReadImage(file, format), image)) << type;
  }
}

TEST(ImageFile, AnAllZeroDepthMapStaysSixteenBit) {
  sortcell_test::TempDir dir;
  const cv::Mat zeros(4, 5, CV_16UC1, cv::Scalar(0));
  ASSERT_TRUE(WritePng(dir.path() / "depth.png", zeros));
  EXPECT_TRUE(Same(ReadImage(dir.path() / "depth.png", PixelFormat::kGrey16), zeros));
}

TEST(ImageFile, ColourAndGreyConvertAsOpenCvReads) {
  sortcell_test::TempDir dir;
  const cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(10, 100, 200));  // B, G, R
  ASSERT_TRUE(WritePng(dir.path() / "colour.png", bgr));
  const cv::Mat grey = ReadImage(dir.path() / "colour.png", PixelFormat::kGrey8);
  ASSERT_EQ(grey.type(), CV_8UC1);
  EXPECT_NEAR(grey.at<uint8_t>(0, 0), 0.114 * 10 + 0.587 * 100 + 0.299 * 200, 1);
  // An 8-bit file is no depth map.
  EXPECT_TRUE(ReadImage(dir.path() / "colour.png", PixelFormat::kGrey16).empty());
  ASSERT_TRUE(WritePng(dir.path() / "grey.png", cv::Mat(2, 2, CV_8UC1, cv::Scalar(77))));
  EXPECT_EQ(ReadImage(dir.path() / "grey.png", PixelFormat::kBgr8).at<cv::Vec3b>(1, 1), cv::Vec3b(77, 77, 77));
}

TEST(ImageFile, AJpegTextureDecodes) {
  sortcell_test::TempDir dir;
  sortcell_test::WriteJpeg(dir.path() / "skin.jpg", cv::Mat(16, 16, CV_8UC3, cv::Scalar(40, 60, 200)));
  const cv::Mat image = ReadImage(dir.path() / "skin.jpg", PixelFormat::kBgr8);
  ASSERT_EQ(image.type(), CV_8UC3);
  const cv::Scalar mean = cv::mean(image);
  EXPECT_NEAR(mean[0], 40, 3);
  EXPECT_NEAR(mean[2], 200, 3);
  EXPECT_NEAR(cv::mean(ReadImage(dir.path() / "skin.jpg", PixelFormat::kGrey8))[0],
              0.114 * 40 + 0.587 * 60 + 0.299 * 200, 3);
  // A grey JPEG spread to three channels.
  sortcell_test::WriteJpeg(dir.path() / "grey.jpg", cv::Mat(16, 16, CV_8UC1, cv::Scalar(90)));
  const cv::Vec3b grey = ReadImage(dir.path() / "grey.jpg", PixelFormat::kBgr8).at<cv::Vec3b>(3, 3);
  EXPECT_NEAR(grey[0], 90, 2);
  EXPECT_EQ(grey[0], grey[2]);
}

TEST(ImageFile, WhatDoesNotDecodeIsEmpty) {
  sortcell_test::TempDir dir;
  std::ofstream(dir.path() / "text.png") << "not an image";
  EXPECT_TRUE(ReadImage(dir.path() / "text.png", PixelFormat::kBgr8).empty());
  std::ofstream(dir.path() / "cut.jpg", std::ios::binary) << "\xFF\xD8\xFF\xE0";
  EXPECT_TRUE(ReadImage(dir.path() / "cut.jpg", PixelFormat::kBgr8).empty());
  EXPECT_TRUE(ReadImage(dir.path() / "missing.png", PixelFormat::kBgr8).empty());
  EXPECT_TRUE(ReadImage(dir.path(), PixelFormat::kBgr8).empty());  // A folder.
  EXPECT_FALSE(WritePng(dir.path() / "no_folder" / "x.png", Gradient(CV_8UC3)));
  EXPECT_FALSE(WritePng(dir.path() / "float.png", cv::Mat(2, 2, CV_32FC1, cv::Scalar(1))));
}

}  // namespace
}  // namespace sortcell::assets
