// The arm-in-view check's capsules against the simulated arm (sim): every geom of the UR5 and the
// gripper, at random joints, lies inside the capsules that stand for them.
#include <gtest/gtest.h>

#include <random>

#include "cell/arm_view.h"
#include "sim/arm_io.h"
#include "sim/model.h"
#include "source_tree.h"

namespace sortcell::sim {
namespace {

using sortcell_test::kCell;

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double u = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + u * (b - a) - p).norm();
}

TEST(ArmCapsules, CoverTheSimulatedArmsGeoms) {
  const Model model = Model::FromFile(kCell);
  Data data(model);
  const ArmIo arm(model);
  const int base = mj_name2id(model.get(), mjOBJ_BODY, "base_link");
  ASSERT_GE(base, 0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int n = 0; n < 50; ++n) {
    robot::Joints q;
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    mj_resetData(model.get(), data.get());
    arm.SetArmPosition(data, q);
    mj_forward(model.get(), data.get());
    const std::vector<cell::Capsule> capsules = cell::ArmCapsules(q, std::nullopt);
    for (int g = 0; g < model->ngeom; ++g) {
      // The arm's and the gripper's geoms: bodies below base_link.
      int b = model->geom_bodyid[g];
      while (b != 0 && b != base) b = model->body_parentid[b];
      if (b != base) continue;
      const Eigen::Vector3d p(data->geom_xpos[3 * g], data->geom_xpos[3 * g + 1], data->geom_xpos[3 * g + 2]);
      double inside = 1e9;
      for (const auto& c : capsules) inside = std::min(inside, DistanceToSegment(p, c.a, c.b) - c.radius);
      EXPECT_LE(inside, 0.0) << "geom " << g << " of body "
                             << mj_id2name(model.get(), mjOBJ_BODY, model->geom_bodyid[g]);
    }
  }
}

}  // namespace
}  // namespace sortcell::sim
