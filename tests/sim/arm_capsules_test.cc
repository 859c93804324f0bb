// The arm-in-view check's capsules against the simulated arm (sim): every geom of the UR5 and the
// gripper, at random joints, lies inside the capsules that stand for them (the URDF's collision
// envelope and the gripper's, margin included), sampled over its surface, not only at its centre.
#include <gtest/gtest.h>

#include <map>
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

// Points over geom g's surface (world frame): rings along a cylinder or capsule (and a capsule's caps),
// a box's corners, or the centre of any other shape.
std::vector<Eigen::Vector3d> SurfaceSamples(const Model& model, const Data& data, int g) {
  const Eigen::Vector3d centre(data->geom_xpos[3 * g], data->geom_xpos[3 * g + 1], data->geom_xpos[3 * g + 2]);
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R(data->geom_xmat + 9 * g);
  const mjtNum* size = model->geom_size + 3 * g;
  std::vector<Eigen::Vector3d> points;
  switch (model->geom_type[g]) {
    case mjGEOM_CYLINDER:
    case mjGEOM_CAPSULE:
      for (int level = -2; level <= 2; ++level) {
        for (int k = 0; k < 16; ++k) {
          const double t = 2 * M_PI * k / 16;
          points.push_back(centre +
                           R * Eigen::Vector3d(size[0] * std::cos(t), size[0] * std::sin(t), 0.5 * level * size[1]));
        }
      }
      if (model->geom_type[g] == mjGEOM_CAPSULE) {
        points.push_back(centre + R * Eigen::Vector3d(0, 0, size[1] + size[0]));
        points.push_back(centre - R * Eigen::Vector3d(0, 0, size[1] + size[0]));
      }
      break;
    case mjGEOM_BOX:
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
        points.push_back(centre + R * sign.cwiseProduct(Eigen::Vector3d(size[0], size[1], size[2])));
      }
      break;
    default:
      points.push_back(centre);
  }
  return points;
}

TEST(ArmCapsules, CoverTheSimulatedArmsGeoms) {
  const Model model = Model::FromFile(kCell);
  Data data(model);
  const ArmIo arm(model);
  const int base = mj_name2id(model.get(), mjOBJ_BODY, "base_link");
  ASSERT_GE(base, 0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  // The arm's and the gripper's geoms (bodies below base_link), each with how far any of its points
  // lay outside every capsule, over all the joints tried.
  std::map<int, double> worst_outside;
  for (int g = 0; g < model->ngeom; ++g) {
    int b = model->geom_bodyid[g];
    while (b != 0 && b != base) b = model->body_parentid[b];
    if (b == base) worst_outside[g] = -1e9;
  }
  for (int n = 0; n < 50; ++n) {
    robot::Joints q;
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    mj_resetData(model.get(), data.get());
    arm.SetArmPosition(data, q);
    mj_forward(model.get(), data.get());
    const cell::CapsuleList capsules = cell::ArmCapsules(q, std::nullopt);
    for (auto& [g, outside] : worst_outside) {
      for (const Eigen::Vector3d& p : SurfaceSamples(model, data, g)) {
        double nearest = 1e9;
        for (const auto& c : capsules) nearest = std::min(nearest, DistanceToSegment(p, c.a, c.b) - c.radius);
        outside = std::max(outside, nearest);
      }
    }
  }
  for (const auto& [g, outside] : worst_outside) {
    EXPECT_LE(outside, 0.0) << "geom " << g << " of body "
                            << mj_id2name(model.get(), mjOBJ_BODY, model->geom_bodyid[g]);
  }
}

}  // namespace
}  // namespace sortcell::sim
