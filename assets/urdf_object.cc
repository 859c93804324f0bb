#include "assets/urdf_object.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sortcell::assets {
namespace {

class UrdfReader {
 public:
  UrdfReader(std::filesystem::path folder, std::string name) : folder_(std::move(folder)), name_(std::move(name)) {}

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument("URDF '" + name_ + "': " + what);
  }

  UrdfShape Shape(const urdf::Geometry& geometry, const urdf::Pose& origin, const std::string& where) const {
    UrdfShape shape;
    shape.X_LS = Pose(origin, where);
    switch (geometry.type) {
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        shape.kind = UrdfShape::Kind::kMesh;
        shape.mesh = MeshPath(mesh.filename, where);
        shape.scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        Positive(shape.scale, where + " mesh scale");
        break;
      }
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(geometry);
        shape.kind = UrdfShape::Kind::kBox;
        shape.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
        Positive(shape.size, where + " box size");
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        shape.kind = UrdfShape::Kind::kCylinder;
        shape.size = Eigen::Vector3d(cylinder.radius, cylinder.length, 1);
        Positive(shape.size, where + " cylinder radius and length");
        shape.size.z() = 0;
        break;
      }
      case urdf::Geometry::SPHERE: {
        const auto& sphere = static_cast<const urdf::Sphere&>(geometry);
        shape.kind = UrdfShape::Kind::kSphere;
        shape.size = Eigen::Vector3d(sphere.radius, 1, 1);
        Positive(shape.size, where + " sphere radius");
        shape.size.tail<2>().setZero();
        break;
      }
      default:
        Fail(where + ": geometry kind " + std::to_string(geometry.type) + " (expected mesh, box, cylinder or sphere)");
    }
    return shape;
  }

 private:
  Eigen::Isometry3d Pose(const urdf::Pose& pose, const std::string& where) const {
    const Eigen::Vector3d p(pose.position.x, pose.position.y, pose.position.z);
    const Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
    if (!p.allFinite() || !q.coeffs().allFinite() || std::abs(q.norm() - 1) > 1e-6) {
      Fail(where + ": origin is not a finite pose");
    }
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = q.normalized().toRotationMatrix();
    X.translation() = p;
    return X;
  }

  void Positive(const Eigen::Vector3d& v, const std::string& what) const {
    if (!v.allFinite() || (v.array() <= 0).any()) Fail(what + " must be positive and finite");
  }

  std::filesystem::path MeshPath(const std::string& filename, const std::string& where) const {
    if (filename.empty()) Fail(where + ": mesh without a filename");
    if (filename.rfind("package://", 0) == 0) {
      Fail(where + ": mesh '" + filename + "' is a ROS package path (expected a path relative to the URDF)");
    }
    std::string path = filename;
    if (path.rfind("file://", 0) == 0) path = path.substr(7);
    const std::filesystem::path mesh = (folder_ / path).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(mesh, ec)) Fail(where + ": mesh file '" + mesh.string() + "' not found");
    return mesh;
  }

  std::filesystem::path folder_;
  std::string name_;
};

}  // namespace

UrdfObject ParseUrdfObject(const std::string& text, const std::filesystem::path& folder, const std::string& name) {
  const UrdfReader reader(folder, name);
  // urdfdom reports parse errors through console_bridge on stderr; we report them ourselves.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    reader.Fail(std::string("not a valid URDF (") + e.what() + ")");
  }
  if (!model) reader.Fail("not a valid URDF (urdfdom could not parse it)");
  if (model->links_.size() != 1) {
    reader.Fail("expected one link (a rigid object), found " + std::to_string(model->links_.size()));
  }
  const urdf::Link& link = *model->links_.begin()->second;
  UrdfObject object;
  object.name = model->getName();
  for (size_t i = 0; i < link.visual_array.size(); ++i) {
    const auto& visual = link.visual_array[i];
    if (!visual || !visual->geometry) reader.Fail("visual " + std::to_string(i) + " has no geometry");
    object.visuals.push_back(reader.Shape(*visual->geometry, visual->origin, "visual " + std::to_string(i)));
  }
  for (size_t i = 0; i < link.collision_array.size(); ++i) {
    const auto& collision = link.collision_array[i];
    if (!collision || !collision->geometry) reader.Fail("collision " + std::to_string(i) + " has no geometry");
    object.collisions.push_back(
        reader.Shape(*collision->geometry, collision->origin, "collision " + std::to_string(i)));
  }
  if (object.collisions.empty()) reader.Fail("link '" + link.name + "' has no <collision> geometry");
  if (link.inertial) {
    const double mass = link.inertial->mass;
    if (!std::isfinite(mass) || mass <= 0)
      reader.Fail("mass " + std::to_string(mass) + " (expected a positive number)");
    object.mass = mass;
  }
  return object;
}

UrdfObject ReadUrdfObject(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec) || !in) {
    throw std::invalid_argument("URDF '" + file.string() + "': file not found");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return ParseUrdfObject(text.str(), std::filesystem::absolute(file).parent_path(), file.string());
}

}  // namespace sortcell::assets
