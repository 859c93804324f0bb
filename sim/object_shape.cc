#include "sim/object_shape.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/ground_truth.h"

namespace sortcell::sim {
namespace {

// A geom as points (body frame) each swollen by a radius: box corners, cylinder rims, capsule ends,
// sphere centres, ellipsoid surface points, mesh vertices (MuJoCo collides with their hull).
struct Swollen {
  Eigen::Vector3d p_B;
  double radius = 0;
};

constexpr int kRimPoints = 24;     // Per cylinder rim: the polygon circumscribes the circle.
constexpr int kCirclePoints = 12;  // Per swollen point in the outline.
constexpr int kEllipsoidLatitudes = 12;
// Taller than this times its narrowest width: the object can lie on its side (a bottle, a box).
constexpr double kLyingAspect = 1.3;

void AddGeom(const mjModel* m, int g, std::vector<Swollen>& parts) {
  const Eigen::Vector3d c(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
  const Eigen::Quaterniond q(m->geom_quat[4 * g], m->geom_quat[4 * g + 1], m->geom_quat[4 * g + 2],
                             m->geom_quat[4 * g + 3]);
  const double* s = m->geom_size + 3 * g;
  const auto local = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return c + q * p; };
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
      for (int k = 0; k < 8; ++k) {
        parts.push_back({local({k & 1 ? s[0] : -s[0], k & 2 ? s[1] : -s[1], k & 4 ? s[2] : -s[2]}), 0});
      }
      break;
    case mjGEOM_CYLINDER: {
      const double r = s[0] / std::cos(M_PI / kRimPoints);
      for (int k = 0; k < kRimPoints; ++k) {
        const double a = 2 * M_PI * k / kRimPoints;
        for (const double z : {-s[1], s[1]}) parts.push_back({local({r * std::cos(a), r * std::sin(a), z}), 0});
      }
      break;
    }
    case mjGEOM_CAPSULE:
      for (const double z : {-s[1], s[1]}) parts.push_back({local({0, 0, z}), s[0]});
      break;
    case mjGEOM_SPHERE:
      parts.push_back({c, s[0]});
      break;
    case mjGEOM_ELLIPSOID:  // Its surface on a latitude-longitude grid: within 0.3 mm for the sets' sizes.
      for (int lat = 0; lat <= kEllipsoidLatitudes; ++lat) {
        const double polar = M_PI * lat / kEllipsoidLatitudes;
        for (int k = 0; k < kRimPoints; ++k) {
          const double a = 2 * M_PI * k / kRimPoints;
          parts.push_back({local({s[0] * std::sin(polar) * std::cos(a), s[1] * std::sin(polar) * std::sin(a),
                                  s[2] * std::cos(polar)}),
                           0});
        }
      }
      break;
    case mjGEOM_MESH: {
      const int mesh = m->geom_dataid[g];
      const float* v = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
      for (int k = 0; k < m->mesh_vertnum[mesh]; ++k)
        parts.push_back({local({v[3 * k], v[3 * k + 1], v[3 * k + 2]}), 0});
      break;
    }
    default:
      parts.push_back({c, m->geom_rbound[g]});
      break;  // The rest: bounding sphere.
  }
}

std::vector<Swollen> CollisionParts(const Model& model, int body) {
  const mjModel* m = model.get();
  std::vector<Swollen> parts;
  for (const int g : CollisionGeoms(m, body)) {
    if (m->geom_type[g] != mjGEOM_PLANE) AddGeom(m, g, parts);
  }
  if (parts.empty()) {
    throw std::invalid_argument("scene '" + model.source() + "': body " + std::to_string(body) +
                                " has no collision geom to rest on");
  }
  return parts;
}

std::vector<Eigen::Vector2d> ConvexOutline(const std::vector<Swollen>& parts, const Eigen::Quaterniond& q_tilt) {
  std::vector<cv::Point2f> points;
  for (const Swollen& part : parts) {
    const Eigen::Vector3d p = q_tilt * part.p_B;
    if (part.radius <= 0) {
      points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
      continue;
    }
    const double r = part.radius / std::cos(M_PI / kCirclePoints);
    for (int k = 0; k < kCirclePoints; ++k) {
      const double a = 2 * M_PI * k / kCirclePoints;
      points.emplace_back(static_cast<float>(p.x() + r * std::cos(a)), static_cast<float>(p.y() + r * std::sin(a)));
    }
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull, /*clockwise=*/false);
  std::vector<Eigen::Vector2d> outline;
  for (const auto& p : hull) outline.emplace_back(p.x, p.y);
  // OpenCV's "counter-clockwise" is in image coordinates (y down): make it so with y up.
  double area2 = 0;
  for (size_t i = 0; i < outline.size(); ++i) {
    const auto& a = outline[i];
    const auto& b = outline[(i + 1) % outline.size()];
    area2 += a.x() * b.y() - a.y() * b.x();
  }
  if (area2 < 0) std::reverse(outline.begin(), outline.end());
  return outline;
}

RestingShape Resting(const std::vector<Swollen>& parts, const Eigen::Quaterniond& q_tilt) {
  RestingShape shape;
  shape.q_tilt = q_tilt;
  double low = INFINITY, high = -INFINITY;
  for (const Swollen& part : parts) {
    const double z = (q_tilt * part.p_B).z();
    low = std::min(low, z - part.radius);
    high = std::max(high, z + part.radius);
  }
  shape.origin_z = -low;
  shape.height = high - low;
  shape.outline = ConvexOutline(parts, q_tilt);
  Eigen::Vector2d corner_low = Eigen::Vector2d::Constant(INFINITY), corner_high = -corner_low;
  for (const auto& v : shape.outline) {
    shape.radius = std::max(shape.radius, v.norm());
    corner_low = corner_low.cwiseMin(v);
    corner_high = corner_high.cwiseMax(v);
  }
  shape.middle = 0.5 * (corner_low + corner_high);
  for (const auto& v : shape.outline) shape.middle_radius = std::max(shape.middle_radius, (v - shape.middle).norm());
  return shape;
}

// The polygon's narrowest width (over its edges' normals, where a convex polygon's is found).
double NarrowestWidth(const std::vector<Eigen::Vector2d>& outline) {
  double narrowest = INFINITY;
  for (size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d edge = outline[(i + 1) % outline.size()] - outline[i];
    if (edge.norm() < 1e-9) continue;
    const Eigen::Vector2d n(-edge.y() / edge.norm(), edge.x() / edge.norm());
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& v : outline) {
      lo = std::min(lo, n.dot(v));
      hi = std::max(hi, n.dot(v));
    }
    narrowest = std::min(narrowest, hi - lo);
  }
  return narrowest;
}

// The upright footprint's radius, geom by geom (capsules and cylinders stand upright in the object
// models; a tilted one is bounded by its bounding sphere). A mesh (an imported object's collision
// piece) by its vertices: its bounding sphere counts its height and is centred off the body's axis
// (an imported plate's disc was 0.15 m for a 0.11 m plate, and two never fitted the table apart).
double DiscRadius(const mjModel* m, int body) {
  double radius = 0;
  for (const int g : CollisionGeoms(m, body)) {
    if (m->geom_type[g] == mjGEOM_MESH) {
      std::vector<Swollen> vertices;
      AddGeom(m, g, vertices);
      for (const auto& v : vertices) radius = std::fmax(radius, v.p_B.head<2>().norm());
      continue;
    }
    const double* s = m->geom_size + 3 * g;
    double r = m->geom_rbound[g];
    switch (m->geom_type[g]) {
      case mjGEOM_SPHERE:
      case mjGEOM_CYLINDER:
      case mjGEOM_CAPSULE:
        r = s[0];
        break;
      case mjGEOM_ELLIPSOID:
        r = std::fmax(s[0], s[1]);
        break;
      case mjGEOM_BOX:
        r = std::hypot(s[0], s[1]);
        break;
      case mjGEOM_PLANE:
        continue;
      default:
        break;
    }
    radius = std::fmax(radius, std::hypot(m->geom_pos[3 * g], m->geom_pos[3 * g + 1]) + r);
  }
  return radius;
}

}  // namespace

ObjectShape ObjectShapeOf(const Model& model, int body) {
  const std::vector<Swollen> parts = CollisionParts(model, body);
  ObjectShape shape;
  shape.disc_radius = DiscRadius(model.get(), body);
  shape.upright = Resting(parts, Eigen::Quaterniond::Identity());
  if (shape.upright.height < kLyingAspect * NarrowestWidth(shape.upright.outline)) return shape;
  // On its side: turned a quarter about x or about y, whichever rests lower (a box on its largest face).
  for (const Eigen::Vector3d axis : {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()}) {
    RestingShape side = Resting(parts, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, axis)));
    if (!shape.lying || side.height < shape.lying->height - 1e-6) shape.lying = std::move(side);
  }
  return shape;
}

std::vector<Eigen::Vector2d> PlacedOutline(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& centre,
                                           double yaw) {
  const Eigen::Rotation2Dd turn(yaw);
  std::vector<Eigen::Vector2d> placed;
  placed.reserve(outline.size());
  for (const auto& v : outline) placed.push_back(centre + turn * v);
  return placed;
}

// Separating axes by hand: OpenCV's intersectConvexConvex gives an overlap area in float, not the
// signed distance a gap between footprints needs.
double Separation(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  double best = -INFINITY;
  for (const auto* polygon : {&a, &b}) {
    const auto& p = *polygon;
    for (size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d edge = p[(i + 1) % p.size()] - p[i];
      if (edge.norm() < 1e-12) continue;
      const Eigen::Vector2d n = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
      double a_lo = INFINITY, a_hi = -INFINITY, b_lo = INFINITY, b_hi = -INFINITY;
      for (const auto& v : a) {
        a_lo = std::min(a_lo, n.dot(v));
        a_hi = std::max(a_hi, n.dot(v));
      }
      for (const auto& v : b) {
        b_lo = std::min(b_lo, n.dot(v));
        b_hi = std::max(b_hi, n.dot(v));
      }
      best = std::max(best, std::max(b_lo - a_hi, a_lo - b_hi));
    }
  }
  return best;
}

}  // namespace sortcell::sim
