#include "sim/object_placement.h"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>
#include <string>

namespace sortcell::sim {
namespace {

// Parked objects float high above the cell: every camera looks down from below this height, and up
// there nothing touches them (below the floor plane, everything would be in contact with it).
constexpr double kParkHeight = 10.0;

int FreeJointQposAddress(const Model& model, int body) {
  const mjModel* m = model.get();
  const int joint = body >= 0 && body < m->nbody ? m->body_jntadr[body] : -1;
  if (joint < 0 || m->jnt_type[joint] != mjJNT_FREE) {
    throw std::invalid_argument("scene '" + model.source() + "': body " + std::to_string(body) +
                                " is not a free body (an object)");
  }
  return m->jnt_qposadr[joint];
}

void SetFreePose(const Model& model, Data& data, int body, const Eigen::Vector3d& p, const Eigen::Quaterniond& q_WB) {
  const int q = FreeJointQposAddress(model, body);
  double* qpos = data->qpos + q;
  qpos[0] = p.x();
  qpos[1] = p.y();
  qpos[2] = p.z();
  qpos[3] = q_WB.w();
  qpos[4] = q_WB.x();
  qpos[5] = q_WB.y();
  qpos[6] = q_WB.z();
  const int v = model->jnt_dofadr[model->body_jntadr[body]];
  for (int i = 0; i < 6; ++i) data->qvel[v + i] = 0;
}

void SetFreePose(const Model& model, Data& data, int body, const Eigen::Vector3d& p, double yaw) {
  SetFreePose(model, data, body, p, Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())));
}

}  // namespace

void PlaceObject(const Model& model, Data& data, int body, double x, double y, double yaw) {
  SetFreePose(model, data, body, Eigen::Vector3d(x, y, 0), yaw);
}

void PlaceObject(const Model& model, Data& data, int body, const TablePose& pose, const ObjectShape& shape) {
  if (pose.lying && !shape.lying) {
    throw std::invalid_argument("scene '" + model.source() + "': body " + std::to_string(body) +
                                " cannot lie on its side (not taller than it is narrow)");
  }
  const RestingShape& resting = shape.Resting(pose.lying);
  const Eigen::Quaterniond q_WB =
      Eigen::Quaterniond(Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ())) * resting.q_tilt;
  SetFreePose(model, data, body, Eigen::Vector3d(pose.x, pose.y, resting.origin_z), q_WB.normalized());
}

void ParkObject(const Model& model, Data& data, int body, int slot) {
  SetFreePose(model, data, body, Eigen::Vector3d(0.5 * (slot % 10), 0.5 * (slot / 10), kParkHeight), 0);
}

void StowObject(const Model& model, Data& data, int body, int slot) {
  SetFreePose(model, data, body, Eigen::Vector3d(-2.5 - 0.4 * (slot % 10), -2.5 - 0.4 * (slot / 10), 0), 0);
}

namespace {

std::optional<std::vector<TablePose>> SampleOnce(const std::vector<double>& radii, const Eigen::Vector2d& min,
                                                 const Eigen::Vector2d& max, double gap, std::mt19937_64& rng,
                                                 int max_tries, std::uniform_real_distribution<double>& unit) {
  std::vector<TablePose> poses;
  for (size_t i = 0; i < radii.size(); ++i) {
    bool placed = false;
    for (int attempt = 0; attempt < max_tries && !placed; ++attempt) {
      const double r = radii[i];
      TablePose pose{min.x() + r + unit(rng) * std::fmax(0.0, max.x() - min.x() - 2 * r),
                     min.y() + r + unit(rng) * std::fmax(0.0, max.y() - min.y() - 2 * r), unit(rng) * 2 * M_PI};
      placed = true;
      for (size_t j = 0; j < poses.size() && placed; ++j) {
        placed = std::hypot(pose.x - poses[j].x, pose.y - poses[j].y) >= r + radii[j] + gap;
      }
      if (placed) poses.push_back(pose);
    }
    if (!placed) return std::nullopt;
  }
  return poses;
}

}  // namespace

std::optional<std::vector<TablePose>> SampleTablePoses(const std::vector<double>& radii, const Eigen::Vector2d& min,
                                                       const Eigen::Vector2d& max, double gap, std::mt19937_64& rng,
                                                       int max_tries) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int arrangement = 0; arrangement < kPlacementArrangements; ++arrangement) {
    if (auto poses = SampleOnce(radii, min, max, gap, rng, max_tries, unit)) return poses;
  }
  return std::nullopt;
}

std::optional<std::vector<TablePose>> SampleTablePoses(const std::vector<double>& radii, const PlacementArea& area,
                                                       std::mt19937_64& rng, int max_tries) {
  return SampleTablePoses(radii, area.min, area.max, area.gap_m, rng, max_tries);
}

}  // namespace sortcell::sim
