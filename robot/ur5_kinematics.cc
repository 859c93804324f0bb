#include "robot/ur5_kinematics.h"

#include <algorithm>
#include <cmath>

#include "robot/gripper_geometry.h"
#include "robot/ur5_dh.h"

namespace sortcell::robot {

Eigen::Isometry3d DhLinkTransform(int i, double q_i) {
  const DhRow& row = kUr5Dh.at(static_cast<size_t>(i));
  // T_{i-1,i} = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i), written out: composing Eigen's AngleAxis rotations
  // cost forward kinematics most of its time (most of all under the sanitizers). Each entry is the
  // arithmetic Eigen's composition does, its zero terms left out, so the frames are the same to the bit
  // (unit test Ur5Kinematics.LinkTransformsEqualEigensComposition): AngleAxis puts (1 - c) + c on the diagonal
  // entry of its own axis, which need not round to 1.
  const double c = std::cos(q_i), s = std::sin(q_i);
  const double ca = std::cos(row.alpha), sa = std::sin(row.alpha);
  const double zz = (1 - c) + c, xx = (1 - ca) + ca;
  Eigen::Isometry3d T;
  T.linear() << c * xx, -s * ca, s * sa,  //
      s * xx, c * ca, -c * sa,            //
      0, zz * sa, zz * ca;
  T.translation() << c * row.a, s * row.a, zz * row.d;
  T.makeAffine();
  return T;
}

LinkFrames ForwardKinematicsAll(const Joints& q) {
  LinkFrames X;
  X[0] = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) X[i + 1] = X[i] * DhLinkTransform(i, q[i]);
  return X;
}

// The closed form uses that joints 2, 3 and 4 are parallel: in frame 1 the arm is a planar chain
// with angles q2, q2+q3, q2+q3+q4, and the wrist adds R46 = Rz(q5) Rx(-pi/2) Rz(q6). Six sin/cos
// pairs instead of twelve keeps FK cheap enough to check every IK solution.
Eigen::Isometry3d FlangePose(const Joints& q) {
  using namespace ur5_lengths;  // NOLINT(google-build-using-namespace): the formulas' own names.
  const double q23 = q[1] + q[2], q234 = q23 + q[3];
  const double c1 = std::cos(q[0]), s1 = std::sin(q[0]);
  const double c2 = std::cos(q[1]), s2 = std::sin(q[1]);
  const double c23 = std::cos(q23), s23 = std::sin(q23);
  const double c234 = std::cos(q234), s234 = std::sin(q234);
  const double c5 = std::cos(q[4]), s5 = std::sin(q[4]);
  const double c6 = std::cos(q[5]), s6 = std::sin(q[5]);

  // Frame 6 in frame 4.
  Eigen::Matrix3d R46;
  R46 << c5 * c6, -c5 * s6, -s5,  //
      s5 * c6, -s5 * s6, c5,      //
      -s6, -c6, 0;
  const Eigen::Vector3d p46(-s5 * d6, c5 * d6, d5);
  // Frame 4 in frame 1: R14 = Rz(q234) Rx(pi/2).
  Eigen::Matrix3d R14;
  R14 << c234, 0, s234,  //
      s234, 0, -c234,    //
      0, 1, 0;
  const Eigen::Vector3d p14(a2 * c2 + a3 * c23, a2 * s2 + a3 * s23, d4);
  // Frame 1 in frame 0: R01 = Rz(q1) Rx(pi/2), p01 = (0, 0, d1).
  Eigen::Matrix3d R01;
  R01 << c1, 0, s1,  //
      s1, 0, -c1,    //
      0, 1, 0;

  Eigen::Isometry3d X;
  X.linear() = R01 * (R14 * R46);
  X.translation() = R01 * (p14 + R14 * p46) + Eigen::Vector3d(0, 0, d1);
  X.makeAffine();
  return X;
}

Eigen::Isometry3d TcpInFlange() { return Eigen::Isometry3d(Eigen::Translation3d(0, 0, kTcpOffsetZ)); }

Eigen::Isometry3d TcpPose(const Joints& q) { return FlangePose(q) * TcpInFlange(); }

Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  if (std::abs(R(2, 0)) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw - roll (or yaw + roll) is defined; put it all in yaw.
    return {0.0, pitch, std::atan2(-R(0, 1), R(1, 1))};
  }
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

double PositionError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

double RotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  // atan2 form of the angle of R_a^T R_b: accurate for tiny angles, where acos((tr - 1) / 2) is not.
  const Eigen::Matrix3d R = a.linear().transpose() * b.linear();
  const Eigen::Vector3d axis(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double sine = 0.5 * axis.norm(), cosine = 0.5 * (R.trace() - 1.0);
  // Below 1e-4 rad, angle = sin(angle) to a relative 2e-9: skip the atan2 (IK checks 8 poses per call).
  if (sine < 1e-4 && cosine > 0) return sine;
  return std::atan2(sine, cosine);
}

}  // namespace sortcell::robot
