// Three independent computations of the UR5's kinematics must agree: the D-H closed form
// (robot/ur5_kinematics), the URDF chain read with urdfdom (robot/urdf_chain) and MuJoCo's
// kinematics of models/ur5/ur5.xml. Also the gripper constants of the robot layer against the MJCF.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

#include "robot/gripper_geometry.h"
#include "robot/ur5_kinematics.h"
#include "robot/urdf_chain.h"
#include "sim/ground_truth.h"
#include "sim/model.h"
#include "temp_dir.h"
#include "source_tree.h"

namespace {

namespace fs = std::filesystem;
namespace robot = sortcell::robot;
namespace sim = sortcell::sim;
using robot::Joints;

using sortcell_test::kRoot;
const std::vector<std::string> kBodies = {"shoulder_link", "upper_arm_link", "forearm_link",
                                          "wrist_1_link",  "wrist_2_link",   "wrist_3_link"};

TEST(KinematicsAgreement, DhUrdfAndMujocoAgreeOver1000Configurations) {
  const robot::UrdfChain urdf = robot::UrdfChain::FromFile((kRoot / "models/ur5/ur5.urdf").string());
  const sim::Model model = sim::Model::FromFile((kRoot / "models/ur5/ur5.xml").string());
  sim::Data data(model);
  const mjModel* m = model.get();
  std::vector<int> qpos_address, body;
  for (const std::string& name : urdf.joint_names()) {
    qpos_address.push_back(m->jnt_qposadr[model.Id(mjOBJ_JOINT, name)]);
  }
  for (const std::string& name : kBodies) body.push_back(model.Id(mjOBJ_BODY, name));
  const int flange = model.Id(mjOBJ_BODY, "flange");

  std::mt19937_64 rng(1000);
  std::uniform_real_distribution<double> angle(-2 * M_PI, 2 * M_PI);
  double worst_position = 0, worst_rotation = 0;
  for (int n = 0; n < 1000; ++n) {
    Joints q;
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    for (int i = 0; i < 6; ++i) data.get()->qpos[qpos_address[i]] = q[i];
    mj_kinematics(m, data.get());

    const robot::LinkFrames dh = robot::ForwardKinematicsAll(q);
    const std::vector<Eigen::Isometry3d> links = urdf.LinkPoses(q);  // 6 moving links + flange
    ASSERT_EQ(links.size(), 7u);
    for (int i = 0; i < 7; ++i) {
      // Link i+1's frame is D-H frame i turned by q_{i+1}; the flange is D-H frame 6.
      Eigen::Isometry3d expected = dh[i];
      if (i < 6) expected.rotate(Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()));
      const Eigen::Isometry3d mujoco = sim::BodyPose(data, i < 6 ? body[i] : flange);
      for (const Eigen::Isometry3d& other : {links[i], mujoco}) {
        worst_position = std::max(worst_position, robot::PositionError(expected, other));
        worst_rotation = std::max(worst_rotation, robot::RotationError(expected, other));
      }
    }
    const Eigen::Isometry3d closed = robot::FlangePose(q);
    worst_position = std::max(worst_position, robot::PositionError(closed, links[6]));
    worst_rotation = std::max(worst_rotation, robot::RotationError(closed, links[6]));
  }
  EXPECT_LT(worst_position, 1e-6);
  EXPECT_LT(worst_rotation, 1e-6);
  std::cout << "worst disagreement over 1000 configurations: " << worst_position << " m, " << worst_rotation
            << " rad\n";
}

TEST(KinematicsAgreement, TcpOfTheGripperModelMatchesTheRobotLayer) {
  const sim::Model model = sim::Model::FromFile((kRoot / "scenes/cell.xml").string());
  sim::Data data(model);
  mj_kinematics(model.get(), data.get());
  const int tcp = model.Id(mjOBJ_SITE, "tcp");
  const int flange = model.Id(mjOBJ_BODY, "flange");
  Eigen::Isometry3d X_WF = sim::BodyPose(data, flange);
  const Eigen::Vector3d p_WT = Eigen::Map<const Eigen::Vector3d>(data.get()->site_xpos + 3 * tcp);
  EXPECT_TRUE((X_WF.inverse() * p_WT).isApprox(robot::TcpInFlange().translation(), 1e-12));
  // The palm (a capsule across the closing direction, y_F): its lowest point and its extent from above.
  const int palm = model.Id(mjOBJ_GEOM, "gripper_palm");
  const double palm_radius = model.get()->geom_size[3 * palm], palm_half_length = model.get()->geom_size[3 * palm + 1];
  EXPECT_NEAR(robot::TcpInFlange().translation().z() - (model.get()->geom_pos[3 * palm + 2] + palm_radius),
              robot::kPalmBeforeTcp, 1e-12);
  EXPECT_NEAR(palm_half_length + palm_radius, robot::kPalmHalfLength, 1e-12);
  EXPECT_NEAR(palm_radius, robot::kPalmHalfWidth, 1e-12);
  const int housing = model.Id(mjOBJ_GEOM, "gripper_housing");  // A cylinder along z_F.
  EXPECT_NEAR(model.get()->geom_size[3 * housing], robot::kHousingRadius, 1e-12);
  EXPECT_NEAR(robot::TcpInFlange().translation().z() -
                  (model.get()->geom_pos[3 * housing + 2] + model.get()->geom_size[3 * housing + 1]),
              robot::kHousingBeforeTcp, 1e-12);
  // Finger stroke: the joint range is the half-gap.
  const int joint = model.Id(mjOBJ_JOINT, "finger_left_joint");
  EXPECT_DOUBLE_EQ(2 * model.get()->jnt_range[2 * joint + 1], robot::kMaxGap);
  // Finger servos: the stiffness and force limit the squeeze is computed from.
  const int servo = model.Id(mjOBJ_ACTUATOR, "finger_left");
  EXPECT_DOUBLE_EQ(model.get()->actuator_gainprm[servo * mjNGAIN], robot::kFingerServoKp);
  EXPECT_DOUBLE_EQ(model.get()->actuator_forcerange[2 * servo + 1], robot::kFingerForceLimit);
  // The pads' friction, as the slip check assumes it.
  const int pad = model.Id(mjOBJ_GEOM, "finger_left_pad_upper");
  EXPECT_DOUBLE_EQ(model.get()->geom_friction[3 * pad], robot::kPadFriction);
  EXPECT_DOUBLE_EQ(model.get()->geom_friction[3 * pad + 1], robot::kPadTwistFriction);
  EXPECT_GT(model.get()->geom_priority[pad], 0) << "the pads' friction is every pad contact's";
  // The calibration marker: its centre on the plate's face where the robot layer has it.
  const int marker = model.Id(mjOBJ_SITE, "calibration_marker");
  const Eigen::Vector3d p_WM = Eigen::Map<const Eigen::Vector3d>(data.get()->site_xpos + 3 * marker);
  EXPECT_TRUE((X_WF.inverse() * p_WM).isApprox(Eigen::Vector3d(robot::kMarkerFaceX, 0, robot::kMarkerCentreZ), 1e-12));
  const int plate = model.Id(mjOBJ_GEOM, "calibration_plate");
  EXPECT_NEAR(model.get()->geom_pos[3 * plate] + model.get()->geom_size[3 * plate], robot::kMarkerFaceX, 1e-12);
}

TEST(UrdfChain, BadFilesAreOneClearError) {
  const sortcell_test::TempDir dir("urdf_chain");
  const std::string urdf = (kRoot / "models/ur5/ur5.urdf").string();
  const auto expect_error = [](const std::function<void()>& f, const std::string& part) {
    try {
      f();
      ADD_FAILURE() << "no exception, expected '" << part << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  expect_error([&] { robot::UrdfChain::FromFile((dir / "missing.urdf").string()); }, "cannot open the file");
  std::ofstream(dir / "garbage.urdf") << "<robot name='x'><link name='a'/><joint name='j'";
  expect_error([&] { robot::UrdfChain::FromFile((dir / "garbage.urdf").string()); }, "not a valid URDF");
  expect_error([&] { robot::UrdfChain::FromFile(urdf, "base_link", "tool0"); }, "no link named 'tool0'");
  expect_error([&] { robot::UrdfChain::FromFile(urdf, "nowhere", "flange"); }, "no link named 'nowhere'");
  expect_error([&] { robot::UrdfChain::FromFile(urdf, "base_link", "wrist_2_link"); }, "expected 6 revolute joints");
  expect_error([&] { robot::UrdfChain::FromFile(urdf, "flange", "base_link"); }, "does not descend from 'flange'");
}

}  // namespace
