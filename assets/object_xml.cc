#include "assets/object_xml.h"

#include <cstdint>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace sortcell::assets {
namespace {

// The cell's object defaults (objects.inc.xml), with rolling friction for every imported object: a
// scanned can or ball rolls like a round one, and the torsional and rolling terms do a box no harm.
constexpr const char* kRollingFriction = "0.01 0.0005";
constexpr double kDefaultFriction = 1.0;

std::string Vector(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(9);
  s << v.x() << ' ' << v.y() << ' ' << v.z();
  return s.str();
}

std::string Quaternion(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  std::ostringstream s;
  s.precision(9);
  s << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
  return s.str();
}

std::string Assets(const std::string& name, const ObjectGeometry& g, const ObjectXmlFiles& files) {
  std::ostringstream xml;
  xml << "  <asset>\n";
  if (!files.texture.empty()) {
    xml << "    <texture name=\"" << name << "_texture\" type=\"2d\" file=\"" << files.texture.string() << "\"/>\n"
        << "    <material name=\"" << name << "_material\" texture=\"" << name
        << "_texture\" specular=\"0.3\" shininess=\"0.3\"/>\n";
  } else {
    xml << "    <material name=\"" << name << "_material\" rgba=\"0.7 0.7 0.7 1\" specular=\"0.3\"/>\n";
  }
  if (!g.visual.triangles.empty())
    xml << "    <mesh name=\"" << name << "_visual\" file=\"" << files.visual.string() << "\"/>\n";
  xml.precision(7);
  for (size_t i = 0; i < g.hulls.size(); ++i) {
    xml << "    <mesh name=\"" << name << "_piece" << i << "\" vertex=\"";
    for (const auto& v : g.hulls[i].vertices) xml << v.x() << ' ' << v.y() << ' ' << v.z() << ' ';
    xml << "\"/>\n";
  }
  xml << "  </asset>\n";
  return xml.str();
}

std::string Inertial(const ImportReport& r, const MassProperties& m) {
  const Eigen::Matrix3d I = m.inertia * (r.mass / m.volume);
  std::ostringstream xml;
  xml.precision(9);
  xml << "      <inertial pos=\"" << Vector(m.centroid) << "\" mass=\"" << r.mass << "\" fullinertia=\"" << I(0, 0)
      << ' ' << I(1, 1) << ' ' << I(2, 2) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 2) << "\"/>\n";
  return xml.str();
}

std::string PrimitiveGeom(const std::string& name, const Primitive& p) {
  const Eigen::Vector3d& s = p.shape.size;
  std::ostringstream xml;
  xml.precision(9);
  xml << "type=\"";
  switch (p.shape.kind) {
    case UrdfShape::Kind::kBox:
      xml << "box\" size=\"" << Vector(s / 2);
      break;
    case UrdfShape::Kind::kCylinder:
      xml << "cylinder\" size=\"" << s.x() << ' ' << s.y() / 2;
      break;
    case UrdfShape::Kind::kSphere:
      xml << "sphere\" size=\"" << s.x();
      break;
    case UrdfShape::Kind::kMesh:
      throw std::logic_error("object '" + name + "': a mesh is not a primitive");
  }
  xml << "\" pos=\"" << Vector(p.shape.X_LS.translation()) << "\" quat=\"" << Quaternion(p.shape.X_LS.linear()) << "\"";
  return xml.str();
}

std::string Geoms(const ObjectSource& source, const ObjectGeometry& g) {
  const std::string& name = source.name;
  const bool seen = g.visual.triangles.empty();  // without a visual mesh the colliders are what the camera sees
  const std::string collision_class = seen ? "object" : "object_collision";
  std::ostringstream friction;
  friction << source.friction.value_or(kDefaultFriction) << ' ' << kRollingFriction;
  const std::string contact =
      "condim=\"6\" friction=\"" + friction.str() + "\"" + (seen ? " material=\"" + name + "_material\"" : "");
  std::ostringstream xml;
  if (!seen) {
    xml << "      <geom name=\"" << name << "_visual\" class=\"object_visual\" type=\"mesh\" mesh=\"" << name
        << "_visual\" material=\"" << name << "_material\" mass=\"0\"/>\n";
  }
  for (size_t i = 0; i < g.hulls.size(); ++i) {
    xml << "      <geom name=\"" << name << "_piece" << i << "\" class=\"" << collision_class
        << "\" type=\"mesh\" mesh=\"" << name << "_piece" << i << "\" " << contact << " mass=\"0\"/>\n";
  }
  for (size_t i = 0; i < g.primitives.size(); ++i) {
    xml << "      <geom name=\"" << name << "_primitive" << i << "\" class=\"" << collision_class << "\" "
        << PrimitiveGeom(name, g.primitives[i]) << " " << contact << " mass=\"0\"/>\n";
  }
  return xml.str();
}

// Where the body stands until the cell places it: on the table's plane (unbounded in MuJoCo 2.2) far
// behind the robot, at a spot drawn from its name, so a set's objects do not all start in one place
// (a dozen overlapping scans overflowed MuJoCo's contact buffer at the first step).
std::string ParkingSpot(const std::string& name) {
  constexpr int kRows = 30;
  constexpr double kSpacing = 0.6;
  const size_t slot = std::hash<std::string>{}(name) % (kRows * kRows);
  std::ostringstream pos;
  pos << -20.0 - kSpacing * static_cast<double>(slot % kRows) << ' '
      << -20.0 - kSpacing * static_cast<double>(slot / kRows) << " 0";
  return pos.str();
}

}  // namespace

std::string ObjectXml(const ObjectSource& source, const ObjectGeometry& geometry, const ImportReport& report,
                      const MassProperties& unit_density, const ObjectXmlFiles& files) {
  std::ostringstream xml;
  xml << "<!-- " << source.name << ": imported by sortcell from " << report.source << " (" << report.collision_pieces
      << " convex collision pieces, " << report.mass << " kg, inertia from the collision volume). Generated: edit the "
      << "source, not this file. -->\n<mujoco>\n"
      << Assets(source.name, geometry, files) << "  <worldbody>\n    <body name=\"" << source.name << "\" pos=\""
      << ParkingSpot(source.name) << "\" childclass=\"object\">\n      <freejoint name=\"" << source.name
      << "_free\"/>\n"
      << Inertial(report, unit_density) << Geoms(source, geometry) << "    </body>\n  </worldbody>\n</mujoco>\n";
  return xml.str();
}

void WriteMsh(const TriangleMesh& mesh, const std::filesystem::path& file) {
  std::ofstream out(file, std::ios::binary);
  const auto put_int = [&out](int32_t v) { out.write(reinterpret_cast<const char*>(&v), sizeof v); };
  const auto put_float = [&out](double v) {
    const float f = static_cast<float>(v);
    out.write(reinterpret_cast<const char*>(&f), sizeof f);
  };
  const int32_t n = static_cast<int32_t>(mesh.vertices.size());
  const bool normals = mesh.normals.size() == mesh.vertices.size();
  const bool uvs = mesh.uvs.size() == mesh.vertices.size();
  put_int(n);
  put_int(normals ? n : 0);
  put_int(uvs ? n : 0);
  put_int(static_cast<int32_t>(mesh.triangles.size()));
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) put_float(v[k]);
  if (normals)
    for (const auto& v : mesh.normals)
      for (int k = 0; k < 3; ++k) put_float(v[k]);
  if (uvs)
    for (const auto& v : mesh.uvs)
      for (int k = 0; k < 2; ++k) put_float(v[k]);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) put_int(t[k]);
  out.close();
  if (!out) throw std::runtime_error("cannot write '" + file.string() + "'");
}

}  // namespace sortcell::assets
