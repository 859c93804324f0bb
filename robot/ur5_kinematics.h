#pragma once
/// @file
/// UR5 forward kinematics from the D-H table (robot/ur5_dh.h).
///
/// Frames: B = the UR controller's Base frame = D-H frame 0 = the cell's world frame W (z up).
/// F = the tool flange = D-H frame 6 (z along the tool). T = the gripper's tool centre point, a
/// fixed offset along z_F (robot/gripper_geometry.h). This is the D-H convention of the UR
/// documentation, not ROS ur_kinematics' Rz(pi)-mirrored base: at q = 0 the flange is at
/// (-0.81725, -0.19145, -0.00549) with z_F = (0, -1, 0).

#include <array>

#include <Eigen/Geometry>

namespace sortcell::robot {

/// Joint positions q1..q6 (rad): shoulder pan, shoulder lift, elbow, wrist 1, wrist 2, wrist 3.
using Joints = Eigen::Matrix<double, 6, 1>;

/// X_B0 .. X_B6: the pose of every D-H frame in the Base frame (X_B0 = identity).
using LinkFrames = std::array<Eigen::Isometry3d, 7>;

/// T_{i-1,i}(q_i) of D-H row i (0-based), as a rigid transform.
Eigen::Isometry3d DhLinkTransform(int i, double q_i);

/// Every D-H frame in the Base frame.
LinkFrames ForwardKinematicsAll(const Joints& q);

/// X_BF: the flange (D-H frame 6) in the Base frame. Closed form, no allocation.
Eigen::Isometry3d FlangePose(const Joints& q);

/// X_FT: the gripper's TCP in the flange frame (a translation along z_F).
Eigen::Isometry3d TcpInFlange();

/// X_BT = X_BF * X_FT.
Eigen::Isometry3d TcpPose(const Joints& q);

/// R = Rz(yaw) Ry(pitch) Rx(roll): the roll-pitch-yaw convention of the CLI and the UR pendant's RPY.
Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw);

/// (roll, pitch, yaw) with R = Rz(yaw) Ry(pitch) Rx(roll), pitch in [-pi/2, pi/2]; at pitch = +-pi/2
/// (gimbal lock) roll is set to 0 and yaw carries the whole rotation about z.
Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R);

/// Position error |p_a - p_b| (m) and rotation error (rad, the angle of R_a^T R_b) between two poses.
double PositionError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);
double RotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace sortcell::robot
