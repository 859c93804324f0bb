#include "sim/kinect_colour.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <string>

namespace sortcell::sim {
namespace {

KinectColourParams Plain() {  // Gains and saturation only: no blur, no noise.
  KinectColourParams p;
  p.exposure = 1.0;
  p.white_balance_r = p.white_balance_g = p.white_balance_b = 1.0;
  p.saturation = 1.0;
  p.blur_sigma_px = 0.0;
  p.noise_sigma = 0.0;
  return p;
}

cv::Mat Flat(const cv::Vec3b& rgb) { return cv::Mat(20, 30, CV_8UC3, cv::Scalar(rgb[0], rgb[1], rgb[2])); }

TEST(KinectColour, GainsAndWhiteBalanceScaleEachChannel) {
  KinectColourParams p = Plain();
  p.exposure = 0.8;
  p.white_balance_r = 0.9;
  p.white_balance_b = 1.1;
  std::mt19937_64 rng(1);
  const cv::Vec3b out = ApplyKinectColour(Flat({200, 100, 50}), p, rng).at<cv::Vec3b>(10, 10);
  EXPECT_EQ(out, cv::Vec3b(144, 80, 44));  // 200 * 0.72, 100 * 0.8, 50 * 0.88, rounded.
}

TEST(KinectColour, SaturationScalesChromaAboutTheLuma) {
  KinectColourParams p = Plain();
  p.saturation = 0.0;
  std::mt19937_64 rng(1);
  const cv::Vec3b grey = ApplyKinectColour(Flat({200, 100, 50}), p, rng).at<cv::Vec3b>(0, 0);
  const int luma = static_cast<int>(std::lround(0.299 * 200 + 0.587 * 100 + 0.114 * 50));
  EXPECT_EQ(grey, cv::Vec3b(luma, luma, luma));
  p.saturation = 0.5;
  const cv::Vec3b half = ApplyKinectColour(Flat({200, 100, 50}), p, rng).at<cv::Vec3b>(0, 0);
  EXPECT_EQ(half[0], std::lround((200 + luma) / 2.0));
  EXPECT_EQ(half[2], std::lround((50 + luma) / 2.0));
}

TEST(KinectColour, BlurSoftensAStepAndClipsAtEightBits) {
  cv::Mat step = Flat({0, 0, 0});
  step.colRange(15, 30).setTo(cv::Scalar(255, 255, 255));
  KinectColourParams p = Plain();
  p.blur_sigma_px = 1.0;
  p.exposure = 2.0;  // Bright side clips at 255, never wraps.
  std::mt19937_64 rng(1);
  const cv::Mat out = ApplyKinectColour(step, p, rng);
  EXPECT_GT(out.at<cv::Vec3b>(10, 14)[1], 20);  // The dark side next to the edge picks up light.
  EXPECT_LT(out.at<cv::Vec3b>(10, 14)[1], 255);
  EXPECT_EQ(out.at<cv::Vec3b>(10, 25)[1], 255);
  EXPECT_EQ(out.at<cv::Vec3b>(10, 2)[1], 0);
}

TEST(KinectColour, NoiseIsSeededAndHasTheGivenSpread) {
  KinectColourParams p = Plain();
  p.noise_sigma = 3.0;
  const cv::Mat grey = Flat({128, 128, 128});
  std::mt19937_64 a(7), b(7), c(8);
  const cv::Mat na = ApplyKinectColour(grey, p, a), nb = ApplyKinectColour(grey, p, b),
                nc = ApplyKinectColour(grey, p, c);
  EXPECT_EQ(cv::norm(na, nb, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(na, nc, cv::NORM_INF), 0.0);
  cv::Scalar mean, spread;
  cv::meanStdDev(na.reshape(1), mean, spread);
  EXPECT_NEAR(mean[0], 128, 0.5);
  EXPECT_NEAR(spread[0], 3.0, 0.4);
}

TEST(KinectColour, DisabledLeavesTheRenderAsItIs) {
  KinectColourParams p;
  p.enabled = false;
  std::mt19937_64 rng(1);
  const cv::Mat in = Flat({10, 200, 90});
  EXPECT_EQ(cv::norm(ApplyKinectColour(in, p, rng), in, cv::NORM_INF), 0.0);
}

TEST(KinectColour, TheDefaultsDarkenAndDesaturateLikeTheRealSensor) {
  std::mt19937_64 rng(1);
  const cv::Vec3b out = ApplyKinectColour(Flat({230, 213, 56}), KinectColourParams{}, rng).at<cv::Vec3b>(10, 10);
  EXPECT_LT(out[0], 200);  // Darker (exposure 0.83).
  EXPECT_GT(out[2], 56);   // The blue of a yellow rises (saturation 0.74).
}

TEST(KinectColour, JitterStaysInItsRanges) {
  const KinectColourParams base;
  std::mt19937_64 rng(3);
  for (int i = 0; i < 200; ++i) {
    const KinectColourParams p = JitterColour(base, rng);
    EXPECT_GE(p.exposure, 0.6 * base.exposure);
    EXPECT_LE(p.exposure, 1.2 * base.exposure);
    EXPECT_GE(p.saturation, 0.85 * base.saturation);
    EXPECT_LE(p.saturation, 1.15 * base.saturation);
    EXPECT_NEAR(p.white_balance_b / base.white_balance_b, 1.0, 0.04 + 1e-12);
    EXPECT_EQ(p.blur_sigma_px, base.blur_sigma_px);
  }
}

TEST(KinectColour, BadInputIsRefused) {
  std::mt19937_64 rng(1);
  const auto error = [&rng](const cv::Mat& image, const KinectColourParams& p) {
    try {
      ApplyKinectColour(image, p, rng);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), {}), "Kinect colour model: expected an 8-bit RGB image");
  KinectColourParams p;
  p.saturation = -0.1;
  EXPECT_EQ(error(Flat({1, 2, 3}), p), "Kinect colour model: saturation must be finite and >= 0, got -0.100000");
  p = {};
  p.white_balance_g = -1;
  EXPECT_EQ(error(Flat({1, 2, 3}), p), "Kinect colour model: white_balance_g must be finite and >= 0, got -1.000000");
}

}  // namespace
}  // namespace sortcell::sim
