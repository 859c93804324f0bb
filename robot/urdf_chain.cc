#include "robot/urdf_chain.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sortcell::robot {
namespace {

std::invalid_argument UrdfError(const std::string& path, const std::string& what) {
  return std::invalid_argument("URDF '" + path + "': " + what);
}

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  const urdf::Rotation& r = pose.rotation;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << pose.position.x, pose.position.y, pose.position.z;
  X.linear() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  return X;
}

}  // namespace

UrdfChain UrdfChain::FromFile(const std::string& path, const std::string& base_link, const std::string& tip_link) {
  std::ifstream file(path);
  if (!file) throw UrdfError(path, "cannot open the file");
  std::stringstream text;
  text << file.rdbuf();
  // urdfdom reports parse errors through console_bridge on stderr; we report them ourselves.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text.str());
  if (!model) throw UrdfError(path, "not a valid URDF robot description");
  if (!model->getLink(base_link)) throw UrdfError(path, "no link named '" + base_link + "'");
  urdf::LinkConstSharedPtr link = model->getLink(tip_link);
  if (!link) throw UrdfError(path, "no link named '" + tip_link + "'");

  // Walk up from the tip to the base, then reverse.
  UrdfChain chain;
  std::vector<urdf::JointConstSharedPtr> joints;
  while (link->name != base_link) {
    if (!link->parent_joint) {
      throw UrdfError(path, "link '" + tip_link + "' does not descend from '" + base_link + "'");
    }
    joints.push_back(link->parent_joint);
    link = model->getLink(link->parent_joint->parent_link_name);
  }
  std::reverse(joints.begin(), joints.end());
  for (const auto& joint : joints) {
    Element element{ToIsometry(joint->parent_to_joint_origin_transform), Eigen::Vector3d::UnitZ(), -1};
    if (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::CONTINUOUS) {
      element.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
      if (!(element.axis.norm() > 0.5)) throw UrdfError(path, "joint '" + joint->name + "' has no axis");
      element.axis.normalize();
      element.joint_index = static_cast<int>(chain.joint_names_.size());
      chain.joint_names_.push_back(joint->name);
    } else if (joint->type != urdf::Joint::FIXED) {
      throw UrdfError(path, "joint '" + joint->name + "' is neither revolute nor fixed");
    }
    chain.chain_.push_back(element);
  }
  if (chain.joint_names_.size() != 6) {
    throw UrdfError(path, "expected 6 revolute joints from '" + base_link + "' to '" + tip_link + "', found " +
                              std::to_string(chain.joint_names_.size()));
  }
  return chain;
}

std::vector<Eigen::Isometry3d> UrdfChain::LinkPoses(const Joints& q) const {
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(chain_.size());
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (const Element& e : chain_) {
    X = X * e.X_parent_joint;
    if (e.joint_index >= 0) X.rotate(Eigen::AngleAxisd(q[e.joint_index], e.axis));
    poses.push_back(X);
  }
  return poses;
}

Eigen::Isometry3d UrdfChain::TipPose(const Joints& q) const { return LinkPoses(q).back(); }

}  // namespace sortcell::robot
