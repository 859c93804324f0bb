// The camera pose fitted to point pairs: a known pose recovered through noise, outliers left out,
// too few or collinear pairs refused.
#include "cell/hand_eye_fit.h"

#include <gtest/gtest.h>

#include <random>

namespace sortcell::cell {
namespace {

Eigen::Isometry3d KnownPose() {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() = Eigen::AngleAxisd(2.3, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()).toRotationMatrix();
  X_WC.translation() = Eigen::Vector3d(1.25, 0.02, 0.75);
  return X_WC;
}

// A 3 x 3 x 2 grid of places in the world and their camera-frame sightings through `noise_m` of noise.
void Sightings(double noise_m, std::vector<Eigen::Vector3d>& p_W, std::vector<Eigen::Vector3d>& p_C) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0, noise_m);
  const Eigen::Isometry3d X_CW = KnownPose().inverse();
  for (double x : {0.42, 0.54, 0.66}) {
    for (double y : {-0.2, 0.0, 0.2}) {
      for (double z : {0.17, 0.29}) {
        p_W.emplace_back(x, y, z);
        p_C.push_back(X_CW * p_W.back() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
      }
    }
  }
}

double RotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

TEST(FitCameraPose, RecoversAKnownPoseThroughNoise) {
  std::vector<Eigen::Vector3d> p_W, p_C;
  Sightings(0.0003, p_W, p_C);
  const auto fit = FitCameraPose(p_W, p_C);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->inliers, 18);
  EXPECT_LT((fit->X_WC.translation() - KnownPose().translation()).norm(), 0.001);
  EXPECT_LT(RotationError(fit->X_WC, KnownPose()), 0.001);
  EXPECT_GT(fit->rms_m, 0.0001);  // The noise shows in the residual.
  EXPECT_LT(fit->rms_m, 0.001);
}

TEST(FitCameraPose, LeavesOutSightingsThatDisagree) {
  std::vector<Eigen::Vector3d> p_W, p_C;
  Sightings(0.0002, p_W, p_C);
  p_C[3] += Eigen::Vector3d(0.02, 0, 0);  // Caught mid-swing, or partly hidden.
  p_C[11] += Eigen::Vector3d(0, -0.01, 0.01);
  const auto fit = FitCameraPose(p_W, p_C);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->inliers, 16);
  EXPECT_FALSE(fit->inlier[3]);
  EXPECT_FALSE(fit->inlier[11]);
  EXPECT_GT(fit->residual_m[3], 0.015);
  EXPECT_LT((fit->X_WC.translation() - KnownPose().translation()).norm(), 0.001);
  EXPECT_LT(fit->max_m, 0.002);
}

TEST(FitCameraPose, RefusesTooFewOrCollinearSightings) {
  std::vector<Eigen::Vector3d> p_W, p_C;
  Sightings(0.0, p_W, p_C);
  const std::vector<Eigen::Vector3d> few_W(p_W.begin(), p_W.begin() + 5), few_C(p_C.begin(), p_C.begin() + 5);
  EXPECT_FALSE(FitCameraPose(few_W, few_C).has_value());
  std::vector<Eigen::Vector3d> line_W, line_C;
  const Eigen::Isometry3d X_CW = KnownPose().inverse();
  for (int i = 0; i < 8; ++i) {
    line_W.emplace_back(0.4 + 0.03 * i, 0.1, 0.2);
    line_C.push_back(X_CW * line_W.back());
  }
  EXPECT_FALSE(FitCameraPose(line_W, line_C).has_value()) << "the rotation about the line is free";
  EXPECT_THROW(FitCameraPose(p_W, few_C), std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::cell
