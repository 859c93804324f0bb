#pragma once
/// @file
/// A serial chain read from a URDF file with urdfdom, with its own forward kinematics: the second of
/// the three independent UR5 kinematics (D-H, URDF, MuJoCo) that the tests cross-check.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "robot/ur5_kinematics.h"

namespace sortcell::robot {

class UrdfChain {
 public:
  /// Reads `path` and extracts the chain from `base_link` to `tip_link`, which must hold exactly six
  /// revolute (or continuous) joints; fixed joints are folded in.
  /// @throws std::invalid_argument "URDF '<path>': <what is wrong>" for a missing or malformed file,
  ///         unknown links, a broken chain or a different joint count.
  static UrdfChain FromFile(const std::string& path, const std::string& base_link = "base_link",
                            const std::string& tip_link = "flange");

  /// The six movable joints' names, base to tip.
  const std::vector<std::string>& joint_names() const { return joint_names_; }

  /// X_base,link for the child link of every joint (fixed ones included), base to tip; the last is
  /// the tip link.
  std::vector<Eigen::Isometry3d> LinkPoses(const Joints& q) const;

  /// X_base,tip.
  Eigen::Isometry3d TipPose(const Joints& q) const;

 private:
  struct Element {
    Eigen::Isometry3d X_parent_joint;  ///< The joint's <origin> in the parent link.
    Eigen::Vector3d axis;              ///< Unit, in the joint frame.
    int joint_index;                   ///< Into q, or -1 for a fixed joint.
  };
  std::vector<Element> chain_;
  std::vector<std::string> joint_names_;
};

}  // namespace sortcell::robot
