// The robot's own dynamics model (robot/ur5_dynamics.h) against the simulated arm's: gravity and the
// full inverse dynamics agree in random poses, speeds and accelerations (sim).
#include <gtest/gtest.h>

#include <random>

#include "robot/ur5_dynamics.h"
#include "robot/ur5_limits.h"
#include "sim/arm_io.h"
#include "sim/model.h"
#include "source_tree.h"

namespace sortcell::sim {
namespace {

using sortcell_test::kCell;
// The model takes the fingers half open; the simulated ones are set there too.
constexpr double kHalfOpen = 0.0275;

class Ur5DynamicsAgreement : public ::testing::Test {
 protected:
  Ur5DynamicsAgreement() : model_(Model::FromFile(kCell)), data_(model_), arm_(model_) {
    const char* names[] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                           "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
    for (int i = 0; i < 6; ++i) dof_[i] = model_->jnt_dofadr[mj_name2id(model_.get(), mjOBJ_JOINT, names[i])];
    for (const char* finger : {"finger_left_joint", "finger_right_joint"}) {
      finger_qpos_.push_back(model_->jnt_qposadr[mj_name2id(model_.get(), mjOBJ_JOINT, finger)]);
    }
    model_.mutable_get()->opt.disableflags |= mjDSBL_CONTACT;  // Random poses may pass through the table.
  }

  // M(q) qdd + bias(q, qd) of the simulated arm, at its six joints.
  robot::Joints SimulatedTorque(const robot::Joints& q, const robot::Joints& qd, const robot::Joints& qdd) {
    mj_resetData(model_.get(), data_.get());
    arm_.SetArmPosition(data_, q);
    for (int address : finger_qpos_) data_->qpos[address] = kHalfOpen;
    for (int i = 0; i < 6; ++i) data_->qvel[dof_[i]] = qd[i];
    mj_forward(model_.get(), data_.get());
    std::vector<mjtNum> mass(model_->nv * model_->nv);
    mj_fullM(model_.get(), mass.data(), data_->qM);
    robot::Joints tau;
    for (int i = 0; i < 6; ++i) {
      tau[i] = data_->qfrc_bias[dof_[i]];
      for (int j = 0; j < 6; ++j) tau[i] += mass[dof_[i] * model_->nv + dof_[j]] * qdd[j];
    }
    return tau;
  }

  Model model_;
  Data data_;
  ArmIo arm_;
  std::array<int, 6> dof_{};
  std::vector<int> finger_qpos_;
};

TEST_F(Ur5DynamicsAgreement, GravityAndInverseDynamicsMatchTheSimulatedArm) {
  const robot::Ur5Dynamics dynamics(robot::GripperMassProperties());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  double worst_gravity = 0, worst_full = 0;
  for (int n = 0; n < 200; ++n) {
    robot::Joints q, qd, qdd;
    for (int i = 0; i < 6; ++i) {
      q[i] = M_PI * unit(rng);
      qd[i] = robot::kUr5MaxJointSpeed * unit(rng);
      qdd[i] = 20 * unit(rng);
    }
    const robot::Joints gravity = SimulatedTorque(q, robot::Joints::Zero(), robot::Joints::Zero());
    const robot::Joints full = SimulatedTorque(q, qd, qdd);
    const robot::Joints model_full = dynamics.Gravity(q) + dynamics.Inertial(q, qd, qdd);
    // Relative to each joint's torque limit.
    const robot::Joints limit = robot::Ur5TorqueLimits();
    worst_gravity = std::max(worst_gravity, ((dynamics.Gravity(q) - gravity).array() / limit.array()).abs().maxCoeff());
    worst_full = std::max(worst_full, ((model_full - full).array() / limit.array()).abs().maxCoeff());
  }
  std::printf("largest difference / torque limit: gravity %.2e, inverse dynamics %.2e\n", worst_gravity, worst_full);
  EXPECT_LT(worst_gravity, 1e-3);
  EXPECT_LT(worst_full, 1e-3);
}

TEST_F(Ur5DynamicsAgreement, APayloadAtTheTcpWeighsOnTheShoulder) {
  const robot::Joints q = (robot::Joints() << M_PI, -0.5, 0.5, -M_PI_2, -M_PI_2, 0).finished();
  const robot::Ur5Dynamics bare(robot::GripperMassProperties());
  const double extra = std::abs(robot::CellArmDynamics().Gravity(q)[1]) - std::abs(bare.Gravity(q)[1]);
  // 0.5 kg at about the TCP's horizontal distance from the shoulder axis.
  const double reach = std::hypot(robot::TcpPose(q).translation().x(), robot::TcpPose(q).translation().y());
  EXPECT_NEAR(extra, robot::kPlannedPayloadKg * 9.81 * reach, 0.3);
}

}  // namespace
}  // namespace sortcell::sim
