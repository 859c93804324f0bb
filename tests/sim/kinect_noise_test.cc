// The Kinect v1 noise model on synthetic depth images (no rendering).
#include "sim/kinect_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>

namespace sortcell::sim {
namespace {

CameraIntrinsics Kinect() {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = k.fy = 525.0;
  k.cx = 319.5;
  k.cy = 239.5;
  return k;
}

cv::Mat FlatDepth(double z) { return cv::Mat(480, 640, CV_32FC1, cv::Scalar(z)); }

// A plane through (0, 0, z0) turned by `angle` about the camera's y axis: planar depth per pixel.
cv::Mat Tilted(double z0, double angle) {
  const CameraIntrinsics k = Kinect();
  cv::Mat depth(480, 640, CV_32FC1);
  const double t = std::tan(angle);
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const double x_over_z = (u - k.cx) / k.fx;  // plane: z = z0 + t x
      depth.at<float>(v, u) = static_cast<float>(z0 / (1 - t * x_over_z));
    }
  }
  return depth;
}

struct Stats {
  double mean = 0, stddev = 0;
  int valid = 0;
};

Stats ErrorStats(const cv::Mat& noisy, const cv::Mat& clean) {
  Stats s;
  double sum = 0, sum2 = 0;
  for (int v = 0; v < noisy.rows; ++v) {
    for (int u = 0; u < noisy.cols; ++u) {
      const float z = noisy.at<float>(v, u);
      if (!std::isfinite(z)) continue;
      const double e = z - clean.at<float>(v, u);
      sum += e;
      sum2 += e * e;
      ++s.valid;
    }
  }
  s.mean = sum / s.valid;
  s.stddev = std::sqrt(sum2 / s.valid - s.mean * s.mean);
  return s;
}

// NaN != NaN: depth == depth is false exactly where the depth is invalid.
int InvalidCount(const cv::Mat& depth) {
  return static_cast<int>(depth.total()) - cv::countNonZero(depth == depth);  // NOLINT(misc-redundant-expression)
}

TEST(KinectNoise, AxialSpreadMatchesTheModelAtOneAndTwoMetres) {
  KinectNoiseParams params;
  params.quantize = false;  // Quantisation is checked on its own below.
  for (const double z : {1.0, 2.0}) {
    SCOPED_TRACE(z);
    std::mt19937_64 rng(7);
    const cv::Mat clean = FlatDepth(z);
    const Stats s = ErrorStats(ApplyKinectNoise(clean, Kinect(), params, rng), clean);
    const double sigma = AxialSigma(params, z, 0.0);
    EXPECT_NEAR(sigma, 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4), 1e-12);
    EXPECT_NEAR(s.stddev, sigma, 0.15 * sigma);
    EXPECT_NEAR(s.mean, 0.0, 0.1 * sigma);
    EXPECT_GT(s.valid, 0.99 * 640 * 480);
  }
}

TEST(KinectNoise, DepthLiesOnTheDisparityGrid) {
  const KinectNoiseParams params;
  std::mt19937_64 rng(3);
  const cv::Mat noisy = ApplyKinectNoise(FlatDepth(1.0), Kinect(), params, rng);
  const double scale = params.ir_focal_px * params.baseline_m * params.subpixel;
  int checked = 0;
  for (int v = 0; v < 480; v += 7) {
    for (int u = 0; u < 640; u += 7) {
      const float z = noisy.at<float>(v, u);
      if (!std::isfinite(z)) continue;
      const double steps = scale / z;  // disparity in 1/8 px: an integer
      EXPECT_NEAR(steps, std::round(steps), 1e-3);
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000);
  EXPECT_NEAR(QuantizationStep(params, 1.0), 2.87e-3, 0.01e-3);
  EXPECT_NEAR(QuantizationStep(params, 2.0), 11.5e-3, 0.05e-3);
}

TEST(KinectNoise, ProjectorShadowFallsLeftOfAForegroundEdge) {
  // Background at 2 m, a foreground slab at 1 m filling columns 320..479.
  cv::Mat depth = FlatDepth(2.0);
  depth(cv::Rect(320, 0, 160, 480)).setTo(1.0);
  const CameraIntrinsics k = Kinect();
  const cv::Mat shadow = ProjectorShadowMask(depth, k, 0.075);
  const double expected = k.fx * 0.075 * (1.0 / 1.0 - 1.0 / 2.0);  // ~19.7 px
  for (int v = 0; v < 480; v += 60) {
    const cv::Mat row = shadow.row(v);
    EXPECT_NEAR(cv::countNonZero(row), expected, 1.5) << "row " << v;
    EXPECT_EQ(cv::countNonZero(row.colRange(320, 640)), 0);  // Nothing on or right of the slab.
    EXPECT_EQ(row.at<unsigned char>(0, 319), 255);           // The band touches the edge.
  }
  // With noise on, those pixels have no depth.
  std::mt19937_64 rng(5);
  const cv::Mat noisy = ApplyKinectNoise(depth, k, KinectNoiseParams{}, rng);
  EXPECT_GT(InvalidCount(noisy(cv::Rect(300, 0, 20, 480))), 0.7 * 20 * 480);
  EXPECT_LT(InvalidCount(noisy(cv::Rect(0, 0, 250, 480))), 0.01 * 250 * 480);
}

TEST(KinectNoise, RangeLimitsDropDepth) {
  std::mt19937_64 rng(1);
  EXPECT_EQ(InvalidCount(ApplyKinectNoise(FlatDepth(0.4), Kinect(), {}, rng)), 640 * 480);
  EXPECT_EQ(InvalidCount(ApplyKinectNoise(FlatDepth(4.5), Kinect(), {}, rng)), 640 * 480);
  EXPECT_LT(InvalidCount(ApplyKinectNoise(FlatDepth(3.5), Kinect(), {}, rng)), 640 * 480 / 100);
}

TEST(KinectNoise, GrazingSurfacesLoseDepth) {
  const cv::Mat steep = Tilted(1.5, 84.0 * M_PI / 180.0);
  const cv::Mat gentle = Tilted(1.5, 30.0 * M_PI / 180.0);
  // The incidence angle is recovered from the depth image: ~30 deg at the image centre.
  EXPECT_NEAR(IncidenceAngles(gentle, Kinect()).at<float>(240, 320), 30.0 * M_PI / 180.0, 0.02);
  std::mt19937_64 rng(2);
  cv::Mat centre(ApplyKinectNoise(steep, Kinect(), {}, rng), cv::Rect(300, 200, 40, 80));
  EXPECT_GT(InvalidCount(centre), 0.9 * centre.total());
  cv::Mat gentle_noisy = ApplyKinectNoise(gentle, Kinect(), {}, rng);
  EXPECT_LT(InvalidCount(gentle_noisy), 0.02 * gentle_noisy.total());
}

TEST(KinectNoise, SameSeedSameDepthOtherSeedOtherDepth) {
  const cv::Mat clean = Tilted(1.2, 0.4);
  std::mt19937_64 a(11), b(11), c(12);
  const cv::Mat da = ApplyKinectNoise(clean, Kinect(), {}, a);
  const cv::Mat db = ApplyKinectNoise(clean, Kinect(), {}, b);
  const cv::Mat dc = ApplyKinectNoise(clean, Kinect(), {}, c);
  EXPECT_EQ(std::memcmp(da.data, db.data, da.total() * da.elemSize()), 0);
  EXPECT_NE(std::memcmp(da.data, dc.data, da.total() * da.elemSize()), 0);
}

TEST(KinectNoise, RejectsAnImageOfTheWrongShape) {
  std::mt19937_64 rng(1);
  cv::Mat wrong(10, 10, CV_32FC1, cv::Scalar(1.0));
  try {
    ApplyKinectNoise(wrong, Kinect(), {}, rng);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
  }
}

// A sphere of radius `r` centred `z0` ahead on the optical axis, in front of nothing (NaN around it).
cv::Mat Sphere(double z0, double r) {
  const CameraIntrinsics k = Kinect();
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const double x = (u - k.cx) / k.fx * z0, y = (v - k.cy) / k.fy * z0;  // Near-orthographic: fine at 0.7 m.
      if (x * x + y * y < r * r) depth.at<float>(v, u) = static_cast<float>(z0 - std::sqrt(r * r - x * x - y * y));
    }
  }
  return depth;
}

TEST(KinectNoise, TheCorrelationWindowFlattensASmallSphereAndKeepsItsOutline) {
  const cv::Mat sphere = Sphere(0.7, 0.03);
  const cv::Mat windowed = CorrelationWindowDepth(sphere, 9, 0.02);
  EXPECT_EQ(cv::countNonZero(windowed == windowed), cv::countNonZero(sphere == sphere)) << "no depth added or lost";
  // The centre stays (a symmetric neighbourhood); near the rim the window reaches in: nearer than the sphere.
  EXPECT_NEAR(windowed.at<float>(240, 320), sphere.at<float>(240, 320), 0.0005);
  const int rim_u = 320 + static_cast<int>(0.028 / 0.7 * 525);  // 2 mm inside the outline.
  EXPECT_LT(windowed.at<float>(240, rim_u), sphere.at<float>(240, rim_u) - 0.003);
  // Off (0 or 1) is the input itself.
  EXPECT_EQ(CorrelationWindowDepth(sphere, 1, 0.02).data, sphere.data);
}

TEST(KinectNoise, TheWindowKeepsToOneSurface) {
  // A step of 5 cm: each side keeps its own depth up to the edge.
  cv::Mat step = FlatDepth(1.0);
  step.colRange(320, 640).setTo(1.05);
  const cv::Mat windowed = CorrelationWindowDepth(step, 9, 0.02);
  EXPECT_NEAR(windowed.at<float>(240, 319), 1.0, 1e-6);
  EXPECT_NEAR(windowed.at<float>(240, 320), 1.05, 1e-6);
}

// The window's definition, neighbour by neighbour, for every pixel: the reference of the fast filter.
cv::Mat WindowByDefinition(const cv::Mat& depth, int window, float tolerance) {
  cv::Mat out = depth.clone();
  const int half = window / 2;
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const float z0 = depth.at<float>(v, u);
      if (!std::isfinite(z0)) continue;
      double disparity = 0;
      int n = 0;
      for (int y = std::max(0, v - half); y <= std::min(depth.rows - 1, v + half); ++y) {
        for (int x = std::max(0, u - half); x <= std::min(depth.cols - 1, u + half); ++x) {
          const float z = depth.at<float>(y, x);
          if (std::abs(z - z0) < tolerance) disparity += 1.0 / z, ++n;
        }
      }
      out.at<float>(v, u) = static_cast<float>(n / disparity);
    }
  }
  return out;
}

TEST(KinectNoise, TheFastWindowIsTheWindowsDefinition) {
  // A tilted table, a ball on it, a box edge reaching the image's border, holes of no depth and a lone pixel.
  cv::Mat depth = Tilted(1.0, 0.6);
  const cv::Mat ball = Sphere(0.7, 0.03);
  cv::Mat on_ball;
  cv::compare(ball, ball, on_ball, cv::CMP_EQ);  // NaN compares unequal.
  ball.copyTo(depth, on_ball);
  depth(cv::Rect(0, 0, 200, 120)).setTo(0.9);
  depth(cv::Rect(400, 300, 30, 12)).setTo(std::numeric_limits<float>::quiet_NaN());
  depth.row(479).colRange(0, 300).setTo(std::numeric_limits<float>::quiet_NaN());
  depth.at<float>(10, 630) = 1.5f;
  for (int window : {3, 9}) {
    const cv::Mat fast = CorrelationWindowDepth(depth, window, 0.02),
                  reference = WindowByDefinition(depth, window, 0.02f);
    EXPECT_EQ(cv::countNonZero(fast == fast), cv::countNonZero(reference == reference)) << window << " px";
    cv::Mat difference;
    cv::absdiff(fast, reference, difference);
    cv::Mat no_depth;
    cv::compare(reference, reference, no_depth, cv::CMP_NE);
    difference.setTo(0, no_depth);
    double worst = 0;
    cv::minMaxLoc(difference, nullptr, &worst);
    EXPECT_LT(worst, 1e-6) << window << " px";
  }
}

TEST(KinectNoise, TheWindowRefusesAnEvenWindowAToleranceOfZeroAndAnotherImageType) {
  EXPECT_THROW(CorrelationWindowDepth(FlatDepth(1.0), 8, 0.02), std::invalid_argument);
  EXPECT_THROW(CorrelationWindowDepth(FlatDepth(1.0), 9, 0.0), std::invalid_argument);
  EXPECT_THROW(CorrelationWindowDepth(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000)), 9, 0.02), std::invalid_argument);
  EXPECT_NE(ToString(KinectNoiseParams{}).find("window 9 px"), std::string::npos) << "the cell's Kinect has it on";
}

}  // namespace
}  // namespace sortcell::sim
