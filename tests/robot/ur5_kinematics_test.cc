#include "robot/ur5_kinematics.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "robot/gripper_geometry.h"
#include "robot/ur5_dh.h"

namespace sortcell::robot {
namespace {

TEST(Ur5Kinematics, FlangeAtZeroMatchesTheDesignFacts) {
  const Eigen::Isometry3d X = FlangePose(Joints::Zero());
  EXPECT_NEAR(X.translation().x(), -0.81725, 1e-12);
  EXPECT_NEAR(X.translation().y(), -0.19145, 1e-12);
  EXPECT_NEAR(X.translation().z(), -0.005491, 1e-12);
  EXPECT_TRUE(X.linear().col(2).isApprox(Eigen::Vector3d(0, -1, 0), 1e-12));
}

TEST(Ur5Kinematics, ClosedFormEqualsTheChainOfDhTransforms) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-2 * M_PI, 2 * M_PI);
  for (int n = 0; n < 1000; ++n) {
    Joints q;
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    const Eigen::Isometry3d chain = ForwardKinematicsAll(q)[6];
    const Eigen::Isometry3d closed = FlangePose(q);
    ASSERT_LT(PositionError(chain, closed), 1e-12);
    ASSERT_LT(RotationError(chain, closed), 1e-12);
  }
}

// DhLinkTransform is written out; it must give Eigen's composition of the DH rotations and translation
// to the bit, at random angles and at the special ones (where sines and cosines are 0 or +-1).
TEST(Ur5Kinematics, LinkTransformsEqualEigensComposition) {
  const auto composed = [](int i, double q_i) {
    const DhRow& row = kUr5Dh.at(static_cast<size_t>(i));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.rotate(Eigen::AngleAxisd(q_i, Eigen::Vector3d::UnitZ()));
    T.translate(Eigen::Vector3d(row.a, 0, row.d));
    T.rotate(Eigen::AngleAxisd(row.alpha, Eigen::Vector3d::UnitX()));
    return T;
  };
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> angle(-2 * M_PI, 2 * M_PI);
  std::vector<double> angles{0, M_PI_2, -M_PI_2, M_PI, -M_PI, 2 * M_PI};
  for (int n = 0; n < 2000; ++n) angles.push_back(angle(rng));
  for (int i = 0; i < 6; ++i) {
    for (const double q_i : angles) {
      ASSERT_EQ(DhLinkTransform(i, q_i).matrix(), composed(i, q_i).matrix()) << "link " << i << ", angle " << q_i;
    }
  }
}

TEST(Ur5Kinematics, ToolDownPoseOfTheObserveKeyframe) {
  const Joints q = (Joints() << 0, -M_PI_2, M_PI_2, -M_PI_2, -M_PI_2, 0).finished();
  const Eigen::Isometry3d X_BT = TcpPose(q);
  EXPECT_TRUE(X_BT.linear().col(2).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  EXPECT_NEAR((X_BT.translation() - FlangePose(q).translation()).norm(), kTcpOffsetZ, 1e-12);
}

TEST(Ur5Kinematics, RpyRoundTripAndConvention) {
  const Eigen::Matrix3d R = RotationFromRpy(0.3, -0.4, 2.5);
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(2.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  EXPECT_TRUE(R.isApprox(expected, 1e-14));
  EXPECT_TRUE(RpyFromRotation(R).isApprox(Eigen::Vector3d(0.3, -0.4, 2.5), 1e-12));
  // Gimbal lock: pitch = pi/2, the rotation is still reproduced.
  const Eigen::Matrix3d G = RotationFromRpy(0.2, M_PI_2, 0.5);
  const Eigen::Vector3d rpy = RpyFromRotation(G);
  EXPECT_TRUE(RotationFromRpy(rpy[0], rpy[1], rpy[2]).isApprox(G, 1e-9));
}

TEST(Ur5Kinematics, RotationErrorIsAccurateForTinyAngles) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a;
  b.rotate(Eigen::AngleAxisd(1e-10, Eigen::Vector3d(1, 2, 3).normalized()));
  EXPECT_NEAR(RotationError(a, b), 1e-10, 1e-16);
  b = a;
  b.rotate(Eigen::AngleAxisd(3.0, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(RotationError(a, b), 3.0, 1e-12);
}

}  // namespace
}  // namespace sortcell::robot
