#include "assets/object_geometry.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "assets/mesh_pieces.h"
#include "assets/mesh_reader.h"

namespace sortcell::assets {
namespace {

constexpr int kRimPoints = 24;
// A piece whose hull is this much larger than the piece itself is concave: it collides as its hull.
constexpr double kConcaveHullRatio = 1.15;

Eigen::Vector3d ScaleOf(const UrdfShape& shape, double scale) { return shape.scale * scale; }

// Hull vertices kept per convex piece. A scanned round surface's hull has hundreds of vertices, and
// MuJoCo 2.2's mesh-plane contacts then jump between them every step: a resting lemon kept turning
// at 0.6 rad/s, a mug at 0.15 (sortcell objects check on the YCB set). Fewer, well-spread vertices
// rest still; MuJoCo 2.3 added maxhullvert for the same reason.
constexpr int kMaxHullVertices = 48;

// `points` thinned to `count` by farthest-point sampling (each next point the farthest from those
// kept), which keeps the extremes that shape a hull. Deterministic: starts from the lowest point.
std::vector<Eigen::Vector3d> FarthestPoints(const std::vector<Eigen::Vector3d>& points, int count) {
  if (static_cast<int>(points.size()) <= count) return points;
  std::vector<double> distance(points.size(), std::numeric_limits<double>::infinity());
  size_t next = 0;
  for (size_t i = 1; i < points.size(); ++i) {
    if (points[i].z() < points[next].z()) next = i;
  }
  std::vector<Eigen::Vector3d> kept;
  while (static_cast<int>(kept.size()) < count) {
    kept.push_back(points[next]);
    size_t farthest = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      distance[i] = std::min(distance[i], (points[i] - kept.back()).squaredNorm());
      if (distance[i] > distance[farthest]) farthest = i;
    }
    next = farthest;
  }
  return kept;
}

// The piece's hull, or nothing for a sliver with no volume (a stray triangle of the scan).
std::optional<TriangleMesh> HullOf(const TriangleMesh& piece) {
  try {
    TriangleMesh hull = ConvexHull(piece.vertices);
    if (static_cast<int>(hull.vertices.size()) > kMaxHullVertices) {
      hull = ConvexHull(FarthestPoints(hull.vertices, kMaxHullVertices));
    }
    if (MassPropertiesOf(hull).volume > 1e-9) return hull;
  } catch (const std::invalid_argument&) {
  }
  return std::nullopt;
}

// The convex pieces MuJoCo will collide with: each disconnected piece's hull.
void AddHulls(const TriangleMesh& mesh, const std::string& file, const ImportLimits& limits, ObjectGeometry& g) {
  std::vector<TriangleMesh> pieces = ConnectedPieces(mesh);
  if (static_cast<int>(pieces.size()) > limits.max_pieces) {
    g.warnings.push_back("'" + file + "' has " + std::to_string(pieces.size()) + " disconnected pieces (more than " +
                         std::to_string(limits.max_pieces) + "): it collides as one convex hull");
    pieces = {mesh};
  }
  int dropped = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    std::optional<TriangleMesh> hull = HullOf(pieces[i]);
    if (!hull) {
      ++dropped;
      continue;
    }
    // Only a closed, oriented piece has a volume to compare its hull with (scans often are neither).
    const double solid = IsClosedAndOriented(pieces[i]) ? MassPropertiesOf(pieces[i]).volume : 0;
    const double hulled = MassPropertiesOf(*hull).volume;
    if (solid > 0 && hulled > kConcaveHullRatio * solid) {
      g.warnings.push_back("'" + file + "' piece " + std::to_string(i) + " is concave (its hull is " +
                           std::to_string(static_cast<int>(std::lround(100 * (hulled / solid - 1)))) +
                           " % larger): it collides as its hull; a convex decomposition (e.g. V-HACD's) avoids that");
    }
    g.hulls.push_back(std::move(*hull));
  }
  if (dropped > 0) {
    g.warnings.push_back("'" + file + "': " + std::to_string(dropped) +
                         " piece(s) with no volume ignored for collision");
  }
}

TriangleMesh Join(const TriangleMesh& a, const TriangleMesh& b) {
  if (a.triangles.empty()) return b;
  TriangleMesh out = a;
  const int base = static_cast<int>(a.vertices.size());
  out.vertices.insert(out.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) out.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  const bool normals = !a.normals.empty() && !b.normals.empty(), uvs = !a.uvs.empty() && !b.uvs.empty();
  if (normals)
    out.normals.insert(out.normals.end(), b.normals.begin(), b.normals.end());
  else
    out.normals.clear();
  if (uvs)
    out.uvs.insert(out.uvs.end(), b.uvs.begin(), b.uvs.end());
  else
    out.uvs.clear();
  return out;
}

// A visual mesh (scaled and placed) and its texture, resolved next to the mesh file.
void AddVisual(const TriangleMesh& mesh, const std::string& texture, const std::filesystem::path& file,
               ObjectGeometry& g) {
  g.visual = Join(g.visual, mesh);
  if (texture.empty() || mesh.uvs.empty()) return;
  const std::filesystem::path image = (file.parent_path() / texture).lexically_normal();
  if (g.texture.empty()) {
    g.texture = image;
  } else if (g.texture != image) {
    g.warnings.push_back("'" + file.string() + "': only the first visual mesh's texture is used");
  }
}

// A URDF origin in a link scaled by `scale` about its origin.
Eigen::Isometry3d ScaledPose(Eigen::Isometry3d X, double scale) {
  X.translation() *= scale;
  return X;
}

Primitive ScaledPrimitive(UrdfShape shape, double scale) {
  shape.size *= scale;
  shape.X_LS = ScaledPose(shape.X_LS, scale);
  return {shape};
}

ObjectGeometry FromUrdf(const ObjectSource& source, const ImportLimits& limits) {
  const UrdfObject urdf = ReadUrdfObject(source.urdf);
  ObjectGeometry g;
  g.urdf_mass = urdf.mass;
  for (const auto& v : urdf.visuals) {
    if (v.kind != UrdfShape::Kind::kMesh) continue;  // primitives are seen through their collision geoms
    std::string texture;
    const TriangleMesh mesh = ReadMesh(v.mesh, &texture);
    AddVisual(mesh.Scaled(ScaleOf(v, source.scale)).Transformed(ScaledPose(v.X_LS, source.scale)), texture, v.mesh, g);
  }
  for (const auto& c : urdf.collisions) {
    if (c.kind != UrdfShape::Kind::kMesh) {
      g.primitives.push_back(ScaledPrimitive(c, source.scale));
      continue;
    }
    AddHulls(ReadMesh(c.mesh).Scaled(ScaleOf(c, source.scale)).Transformed(ScaledPose(c.X_LS, source.scale)),
             c.mesh.string(), limits, g);
  }
  return g;
}

ObjectGeometry FromMesh(const ObjectSource& source, const ImportLimits& limits) {
  ObjectGeometry g;
  std::string texture;
  const TriangleMesh mesh = ReadMesh(source.mesh, &texture).Scaled(Eigen::Vector3d::Constant(source.scale));
  AddVisual(mesh, texture, source.mesh, g);
  AddHulls(mesh, source.mesh.string(), limits, g);
  return g;
}

}  // namespace

MassProperties Primitive::Mass() const {
  MassProperties m;
  const Eigen::Vector3d& s = shape.size;
  Eigen::Vector3d d;  // principal inertia per unit density in the shape's frame
  switch (shape.kind) {
    case UrdfShape::Kind::kBox:
      m.volume = s.prod();
      d << s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y();
      d *= m.volume / 12;
      break;
    case UrdfShape::Kind::kCylinder:
      m.volume = M_PI * s.x() * s.x() * s.y();
      d << 3 * s.x() * s.x() + s.y() * s.y(), 3 * s.x() * s.x() + s.y() * s.y(), 6 * s.x() * s.x();
      d *= m.volume / 12;
      break;
    case UrdfShape::Kind::kSphere:
      m.volume = 4.0 / 3 * M_PI * std::pow(s.x(), 3);
      d.setConstant(0.4 * m.volume * s.x() * s.x());
      break;
    case UrdfShape::Kind::kMesh:
      return m;
  }
  const Eigen::Matrix3d R = shape.X_LS.linear();
  m.centroid = shape.X_LS.translation();
  m.inertia = R * d.asDiagonal() * R.transpose();
  return m;
}

std::vector<Eigen::Vector3d> Primitive::ExtentPoints() const {
  std::vector<Eigen::Vector3d> local;
  const Eigen::Vector3d& s = shape.size;
  switch (shape.kind) {
    case UrdfShape::Kind::kBox:
      for (int k = 0; k < 8; ++k)
        local.emplace_back(k & 1 ? s.x() / 2 : -s.x() / 2, k & 2 ? s.y() / 2 : -s.y() / 2,
                           k & 4 ? s.z() / 2 : -s.z() / 2);
      break;
    case UrdfShape::Kind::kCylinder:
      for (int k = 0; k < kRimPoints; ++k) {
        const double a = 2 * M_PI * k / kRimPoints, r = s.x() / std::cos(M_PI / kRimPoints);
        for (const double z : {-s.y() / 2, s.y() / 2}) local.emplace_back(r * std::cos(a), r * std::sin(a), z);
      }
      break;
    case UrdfShape::Kind::kSphere:  // its equator (the footprint a gripper closes across) and its poles
      for (int k = 0; k < kRimPoints; ++k) {
        const double a = 2 * M_PI * k / kRimPoints;
        local.emplace_back(s.x() * std::cos(a), s.x() * std::sin(a), 0);
      }
      for (const double sign : {-1.0, 1.0}) local.push_back(sign * s.x() * Eigen::Vector3d::UnitZ());
      break;
    case UrdfShape::Kind::kMesh:
      break;
  }
  for (auto& p : local) p = shape.X_LS * p;
  return local;
}

std::vector<Eigen::Vector3d> ObjectGeometry::CollisionPoints() const {
  std::vector<Eigen::Vector3d> points;
  for (const auto& h : hulls) points.insert(points.end(), h.vertices.begin(), h.vertices.end());
  for (const auto& p : primitives) {
    const auto extent = p.ExtentPoints();
    points.insert(points.end(), extent.begin(), extent.end());
  }
  return points;
}

MassProperties ObjectGeometry::Mass() const {
  std::vector<MassProperties> parts;
  for (const auto& h : hulls) parts.push_back(MassPropertiesOf(h));
  for (const auto& p : primitives) parts.push_back(p.Mass());
  return Combined(parts);
}

void ObjectGeometry::Recentre() {
  Eigen::AlignedBox3d box;
  for (const auto& p : CollisionPoints()) box.extend(p);
  const Eigen::Vector3d base(box.center().x(), box.center().y(), box.min().z());
  const Eigen::Isometry3d X(Eigen::Translation3d(-base));
  visual = visual.Transformed(X);
  for (auto& h : hulls) h = h.Transformed(X);
  for (auto& p : primitives) p.shape.X_LS = X * p.shape.X_LS;
}

ObjectGeometry ReadObjectGeometry(const ObjectSource& source, const ImportLimits& limits) {
  ObjectGeometry g = source.urdf.empty() ? FromMesh(source, limits) : FromUrdf(source, limits);
  if (g.hulls.empty() && g.primitives.empty()) {
    throw std::invalid_argument("object '" + source.name + "' from '" + source.file().string() +
                                "': its collision geometry spans no volume");
  }
  return g;
}

}  // namespace sortcell::assets
