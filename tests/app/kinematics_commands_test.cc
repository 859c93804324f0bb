#include "app/cli/kinematics_commands.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "robot/ur5_kinematics.h"
#include "run_sortcell.h"

namespace sortcell::app {
namespace {

using sortcell_test::ExpectOneLineError;
using sortcell_test::RunSortcell;

TEST(IkCommand, SolutionsReproduceThePoseAndNearestIsOneOfThem) {
  const nlohmann::json j = IkJson({0.4, -0.2, 0.1, 3.14, 0, -1.57}, {}, false);
  EXPECT_EQ(j["status"], "ok");
  ASSERT_EQ(j["solutions"].size(), 8u);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << 0.4, -0.2, 0.1;
  X.linear() = robot::RotationFromRpy(3.14, 0, -1.57);
  for (const auto& s : j["solutions"]) {
    robot::Joints q;
    for (int i = 0; i < 6; ++i) q[i] = s["q"][i];
    EXPECT_LT(robot::PositionError(robot::FlangePose(q), X), 1e-9);
    EXPECT_LT(robot::RotationError(robot::FlangePose(q), X), 1e-9);
    EXPECT_LT(s["position_error"].get<double>(), 1e-9);
  }
  ASSERT_TRUE(j["nearest"].is_number_integer());
  const int nearest = j["nearest"];
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(
        std::remainder(j["nearest_q"][i].get<double>() - j["solutions"][nearest]["q"][i].get<double>(), 2 * M_PI), 0.0,
        1e-12);
  }
}

TEST(IkCommand, TcpPoseAndUnreachable) {
  const robot::Joints q = (robot::Joints() << 2.9, -1.3, 1.7, -1.97, -1.5708, 0.2).finished();
  const Eigen::Isometry3d X = robot::TcpPose(q);
  const Eigen::Vector3d rpy = robot::RpyFromRotation(X.linear());
  const nlohmann::json j =
      IkJson({X.translation().x(), X.translation().y(), X.translation().z(), rpy[0], rpy[1], rpy[2]},
             {2.9, -1.3, 1.7, -1.97, -1.5708, 0.2}, true);
  ASSERT_EQ(j["status"], "ok");
  const int nearest = j["nearest"];
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(j["nearest_q"][i].get<double>(), q[i], 1e-9);
  EXPECT_GE(nearest, 0);
  const nlohmann::json far = IkJson({2.0, 0, 0.3, 0, 0, 0}, {}, false);
  EXPECT_EQ(far["status"], "unreachable");
  EXPECT_TRUE(far["solutions"].empty());
  EXPECT_TRUE(far["nearest"].is_null());
}

TEST(FkCommand, PoseRotationAndRpyAgree) {
  const nlohmann::json j = FkJson({0, 0, 0, 0, 0, 0}, false);
  EXPECT_NEAR(j["position"][0].get<double>(), -0.81725, 1e-12);
  EXPECT_NEAR(j["position"][1].get<double>(), -0.19145, 1e-12);
  const nlohmann::json t = FkJson({0.3, -1.2, 1.4, -1.8, -1.57, 0.4}, true);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = t["rotation"][r][c];
  }
  EXPECT_TRUE(robot::RotationFromRpy(t["rpy"][0], t["rpy"][1], t["rpy"][2]).isApprox(R, 1e-12));
}

TEST(KinematicsCommands, BadValuesThrowNamingTheOption) {
  EXPECT_THROW(FkJson({1, 2, 3}, false), std::invalid_argument);
  EXPECT_THROW(IkJson({0.4, 0, 0.3, 0, 0, NAN}, {}, false), std::invalid_argument);
  try {
    IkJson({0.4, 0, 0.3, 0, 0, 0}, {1, 2}, false);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--q-near"), std::string::npos);
  }
}

TEST(KinematicsCommands, NegativeNumbersAreValuesOnTheCommandLine) {
  const std::string out = sortcell_test::TestTempDir() + "ik_negative.json";
  const std::string command = std::string(SORTCELL_BINARY) +
                              " ik --pose 0.4 -0.2 0.1 3.14 0 -1.57 --q-near 2.4 -1.3 2.2 -2.5 -1.57 -0.7 > " + out;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["q_near"][1], -1.3);
  // Unreachable exits 1 (a result, not an error) and still prints the JSON.
  EXPECT_EQ(RunSortcell("ik --pose 3 0 0 0 0 0").exit_code, 1);
  EXPECT_EQ(RunSortcell("fk --q 0 -1.9 1.3 -0.97 -1.57 0 --tcp").exit_code, 0);
}

TEST(KinematicsCommands, MalformedInputIsOneLineExitTwo) {
  ExpectOneLineError(RunSortcell("ik --pose 0.4 -0.2 abc 1 2 3"), "--pose");
  ExpectOneLineError(RunSortcell("ik --pose 0.4 -0.2 0.1"), "--pose");
  ExpectOneLineError(RunSortcell("ik --pose 0.4 0.2 0.1 0 0 nan"), "--pose");
  ExpectOneLineError(RunSortcell("ik --pose 0.4 0.2 0.1 0 0 0 --q-near 1 2"), "--q-near");
  ExpectOneLineError(RunSortcell("fk --q 1 2 3 4 5 6 7"), "--q");
  ExpectOneLineError(RunSortcell("fk --q 1 2 3 4 5 x"), "--q");
  ExpectOneLineError(RunSortcell("fk"), "--q");
}

}  // namespace
}  // namespace sortcell::app
