// The joint acceleration limits of robot/ur5_limits.h against the simulated arm's dynamics: at those
// accelerations (any signs, all joints at once) and speeds up to pi rad/s, with the gripper and a 0.5 kg payload,
// the torque M(q) qdd + bias(q, qd) stays within 80 % of each joint's limit in every sampled pose
// whose links are above the table (sim).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "robot/ik_selection.h"
#include "robot/ur5_limits.h"
#include "sim/arm_io.h"
#include "sim/model.h"
#include "source_tree.h"

namespace sortcell::sim {
namespace {

using sortcell_test::kCell;
constexpr double kPayloadKg = 0.5;
constexpr double kBudget = 0.8;  // Of each torque limit; the rest is the feedback's.

TEST(AccelerationLimits, FitTheTorqueLimitsWithPayloadEverywhereAboveTheTable) {
  Model model = Model::FromFile(kCell);
  const int gripper = mj_name2id(model.get(), mjOBJ_BODY, "gripper_base");
  ASSERT_GE(gripper, 0);
  model.mutable_get()->body_mass[gripper] += kPayloadKg;
  Data data(model);
  const ArmIo arm(model);
  std::array<int, 6> dof{};
  const char* names[] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                         "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  for (int i = 0; i < 6; ++i) dof[i] = model->jnt_dofadr[mj_name2id(model.get(), mjOBJ_JOINT, names[i])];

  const robot::Joints acceleration = robot::Ur5AccelerationLimits(), limit = robot::Ur5TorqueLimits();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<mjtNum> mass(model->nv * model->nv);
  robot::Joints worst = robot::Joints::Zero();
  int poses = 0;
  for (int n = 0; n < 4000; ++n) {
    robot::Joints q;
    q << 2 * M_PI * unit(rng), -M_PI * unit(rng), -2.8 + 5.6 * unit(rng), -M_PI + 2 * M_PI * unit(rng),
        -M_PI + 2 * M_PI * unit(rng), -M_PI + 2 * M_PI * unit(rng);
    if (!robot::LinksAboveTable(q, 0.05)) continue;
    ++poses;
    mj_resetData(model.get(), data.get());
    arm.SetArmPosition(data, q);
    for (int i = 0; i < 6; ++i) data->qvel[dof[i]] = (2 * unit(rng) - 1) * robot::kUr5MaxJointSpeed;
    mj_forward(model.get(), data.get());
    mj_fullM(model.get(), mass.data(), data->qM);
    for (int i = 0; i < 6; ++i) {
      double need = std::abs(data->qfrc_bias[dof[i]]);
      for (int j = 0; j < 6; ++j) need += std::abs(mass[dof[i] * model->nv + dof[j]]) * acceleration[j];
      worst[i] = std::max(worst[i], need / limit[i]);
    }
  }
  ASSERT_GT(poses, 1000);
  std::printf("worst torque / limit per joint over %d poses: %.2f %.2f %.2f %.2f %.2f %.2f\n", poses, worst[0],
              worst[1], worst[2], worst[3], worst[4], worst[5]);
  for (int i = 0; i < 6; ++i) EXPECT_LE(worst[i], kBudget) << "joint " << i + 1;
}

}  // namespace
}  // namespace sortcell::sim
