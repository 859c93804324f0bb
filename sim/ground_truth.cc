#include "sim/ground_truth.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace sortcell::sim {
namespace {

// An object standing upright in a bin has its centre of mass up to half its height above the floor
// (0.11 m for the 0.224 m bottles), above the 0.10 m walls: "in the bin" allows up to this height.
constexpr double kBinMaxComHeight = 0.15;

// Half-extent of a geom along unit direction u (world frame), from its primitive shape.
double SupportHalfExtent(const mjModel* m, const mjData* d, int g, const Eigen::Vector3d& u) {
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d->geom_xmat + 9 * g);
  const Eigen::Vector3d v = R.transpose() * u;  // u in the geom frame
  const double* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return s[0];
    case mjGEOM_CAPSULE:
      return s[0] + s[1] * std::abs(v.z());
    case mjGEOM_CYLINDER:
      return s[0] * std::sqrt(std::fmax(0.0, 1.0 - v.z() * v.z())) + s[1] * std::abs(v.z());
    case mjGEOM_ELLIPSOID:
      return Eigen::Vector3d(s[0] * v.x(), s[1] * v.y(), s[2] * v.z()).norm();
    case mjGEOM_BOX:
      return s[0] * std::abs(v.x()) + s[1] * std::abs(v.y()) + s[2] * std::abs(v.z());
    default:
      return m->geom_rbound[g];  // meshes and others: the bounding sphere
  }
}

void ExtentAlong(const mjModel* m, const mjData* d, const std::vector<int>& geoms, const Eigen::Vector3d& u, double& lo,
                 double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const int g : geoms) {
    const double c = u.dot(Eigen::Map<const Eigen::Vector3d>(d->geom_xpos + 3 * g));
    const double e = SupportHalfExtent(m, d, g, u);
    lo = std::fmin(lo, c - e);
    hi = std::fmax(hi, c + e);
  }
}

}  // namespace

std::vector<int> CollisionGeoms(const mjModel* m, int body) {
  std::vector<int> geoms;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == body && (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0)) geoms.push_back(g);
  }
  return geoms;
}

ObjectExtent ObjectExtentOf(const Model& model, const Data& data, int body) {
  const mjModel* m = model.get();
  const std::vector<int> geoms = CollisionGeoms(m, body);
  if (geoms.empty()) {
    throw std::invalid_argument("scene '" + model.source() + "': body '" + mj_id2name(m, mjOBJ_BODY, body) +
                                "' has no collision geom");
  }
  ObjectExtent extent;
  double lo, hi;
  ExtentAlong(m, data.get(), geoms, Eigen::Vector3d::UnitZ(), extent.base_z, extent.top_z);
  extent.width = std::numeric_limits<double>::infinity();
  double middle = 0;
  for (int degree = 0; degree < 180; ++degree) {
    const double yaw = degree * M_PI / 180;
    ExtentAlong(m, data.get(), geoms, Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0), lo, hi);
    if (hi - lo < extent.width - 1e-9) {
      extent.width = hi - lo;
      extent.pinch_yaw = yaw;
      middle = 0.5 * (lo + hi);
    }
  }
  const Eigen::Vector2d u(std::cos(extent.pinch_yaw), std::sin(extent.pinch_yaw)), v(-u.y(), u.x());
  const Eigen::Vector2d com(data->xipos[3 * body], data->xipos[3 * body + 1]);
  extent.centre_xy = middle * u + v.dot(com) * v;
  return extent;
}

Eigen::Isometry3d BodyPose(const Data& data, int body) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Map<const Eigen::Vector3d>(data->xpos + 3 * body);
  X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data->xmat + 9 * body);
  return X;
}

Eigen::Isometry3d SitePose(const Data& data, int site) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Map<const Eigen::Vector3d>(data->site_xpos + 3 * site);
  X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data->site_xmat + 9 * site);
  return X;
}

namespace {
constexpr std::string_view kBinPrefix = "bin_";
}  // namespace

std::string BinName(const std::string& category) { return std::string(kBinPrefix) + category; }

std::vector<BinRef> Bins(const Model& model) {
  std::vector<BinRef> bins;
  for (int b = 0; b < model.get()->nbody; ++b) {
    const char* name = mj_id2name(model.get(), mjOBJ_BODY, b);
    if (!name || std::string_view(name).substr(0, kBinPrefix.size()) != kBinPrefix) continue;
    BinRef bin;
    bin.name = std::string(name).substr(kBinPrefix.size());
    bin.body = b;
    bin.site = mj_name2id(model.get(), mjOBJ_SITE, name);
    if (bin.site < 0 || model.get()->site_type[bin.site] != mjGEOM_BOX) {
      throw std::invalid_argument("scene '" + model.source() + "': bin '" + name + "' has no box site '" + name +
                                  "' (its floor centre, sized to its inside)");
    }
    bin.inner_half = Eigen::Map<const Eigen::Vector2d>(model.get()->site_size + 3 * bin.site);
    bins.push_back(bin);
  }
  return bins;
}

bool InBin(const Data& data, int object_body, const BinRef& bin) {
  const Eigen::Vector3d p_WO = Eigen::Map<const Eigen::Vector3d>(data->xipos + 3 * object_body);
  const Eigen::Vector3d p_BO = BodyPose(data, bin.body).inverse() * p_WO;
  return std::abs(p_BO.x()) < bin.inner_half.x() && std::abs(p_BO.y()) < bin.inner_half.y() && p_BO.z() > 0 &&
         p_BO.z() < kBinMaxComHeight;
}

}  // namespace sortcell::sim
