#include "robot/ur5_ik.h"

#include <cmath>

#include "robot/ur5_dh.h"

namespace sortcell::robot {
namespace {

constexpr double d1 = kUr5Dh[0].d, a2 = kUr5Dh[1].a, a3 = kUr5Dh[2].a;
constexpr double d4 = kUr5Dh[3].d, d5 = kUr5Dh[4].d, d6 = kUr5Dh[5].d;
// A cosine this little past +-1 is rounding at a boundary (elbow straight, wrist aligned) and is
// clamped; anything further is out of reach.
constexpr double kCosineSlack = 1e-9;
constexpr double kDuplicateTolerance = 1e-7;  // rad, per joint, modulo 2 pi

double Wrap(double angle) {
  const double w = std::remainder(angle, 2.0 * M_PI);  // [-pi, pi]
  return w <= -M_PI ? w + 2.0 * M_PI : w;
}

bool ClampCosine(double& c) {
  if (!(std::abs(c) <= 1.0 + kCosineSlack)) return false;  // also rejects NaN
  c = std::fmax(-1.0, std::fmin(1.0, c));
  return true;
}

bool SameModulo2Pi(const Joints& a, const Joints& b) {
  for (int i = 0; i < 6; ++i) {
    if (std::abs(std::remainder(a[i] - b[i], 2.0 * M_PI)) > kDuplicateTolerance) return false;
  }
  return true;
}

// Frame 6 in frame 4 for given q5, q6 (see FlangePose).
Eigen::Isometry3d WristTransform(double q5, double q6) {
  const double c5 = std::cos(q5), s5 = std::sin(q5), c6 = std::cos(q6), s6 = std::sin(q6);
  Eigen::Isometry3d T;
  T.linear() << c5 * c6, -c5 * s6, -s5,  //
      s5 * c6, -s5 * s6, c5,             //
      -s6, -c6, 0;
  T.translation() << -s5 * d6, c5 * d6, d5;
  T.makeAffine();
  return T;
}

// Frame 1 in frame 0 for q1: Rz(q1) Tz(d1) Rx(pi/2).
Eigen::Isometry3d ShoulderTransform(double c1, double s1) {
  Eigen::Isometry3d T;
  T.linear() << c1, 0, s1,  //
      s1, 0, -c1,           //
      0, 1, 0;
  T.translation() << 0, 0, d1;
  T.makeAffine();
  return T;
}

void AddChecked(const Eigen::Isometry3d& X_BF, const Joints& q_raw, bool singular, const IkOptions& options,
                IkResult& result) {
  Joints q;
  for (int i = 0; i < 6; ++i) q[i] = Wrap(q_raw[i]);
  if (!q.allFinite()) return;
  for (int k = 0; k < result.count; ++k) {
    if (SameModulo2Pi(result.solutions[k].q, q)) return;
  }
  const Eigen::Isometry3d X = FlangePose(q);
  const double position_error = PositionError(X, X_BF);
  const double rotation_error = RotationError(X, X_BF);
  if (!(position_error <= options.accept_position && rotation_error <= options.accept_rotation)) return;
  result.solutions[result.count++] = {q, position_error, rotation_error, singular};
}

}  // namespace

IkResult SolveIk(const Eigen::Isometry3d& X_BF, double q6_current, const IkOptions& options) {
  IkResult result;
  const Eigen::Matrix3d& R = X_BF.linear();
  const Eigen::Vector3d& p = X_BF.translation();
  const Eigen::Vector3d p05 = p - d6 * R.col(2);  // the wrist centre (origin of frame 5)
  const double r = std::hypot(p05.x(), p05.y());
  if (!(r > d4) || !R.allFinite()) return result;  // the shoulder column (or NaN input)

  const double psi = std::atan2(p05.y(), p05.x());
  const double phi = std::acos(d4 / r);
  for (const double shoulder : {1.0, -1.0}) {
    const double q1 = psi + shoulder * phi + M_PI_2;
    const double c1 = std::cos(q1), s1 = std::sin(q1);
    // z1 = (s1, -c1, 0); p . z1 = d4 + d6 cos q5.
    double c5 = (p.x() * s1 - p.y() * c1 - d4) / d6;
    if (!ClampCosine(c5)) continue;
    const Eigen::Isometry3d X_10 = ShoulderTransform(c1, s1).inverse();
    for (const double wrist : {1.0, -1.0}) {
      double q5 = wrist * std::acos(c5);
      double s5 = std::sin(q5);
      double q6;
      const bool singular = std::abs(s5) < options.wrist_singular_sin;
      if (singular) {
        q5 = c5 > 0 ? 0.0 : M_PI;
        q6 = q6_current;
      } else {
        // z1 in frame 6 is (s5 c6, -s5 s6, c5).
        const double x6_z1 = R(0, 0) * s1 - R(1, 0) * c1;
        const double y6_z1 = R(0, 1) * s1 - R(1, 1) * c1;
        q6 = std::atan2(-y6_z1 / s5, x6_z1 / s5);
      }
      // The planar chain of joints 2-4 in frame 1.
      const Eigen::Isometry3d X_14 = X_10 * X_BF * WristTransform(q5, q6).inverse();
      const double q234 = std::atan2(X_14.linear()(1, 0), X_14.linear()(0, 0));
      const double px = X_14.translation().x(), py = X_14.translation().y();
      double c3 = (px * px + py * py - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
      if (!ClampCosine(c3)) continue;
      for (const double elbow : {1.0, -1.0}) {
        const double q3 = elbow * std::acos(c3);
        const double q2 = std::atan2(py, px) - std::atan2(a3 * std::sin(q3), a2 + a3 * std::cos(q3));
        Joints q;
        q << q1, q2, q3, q234 - q2 - q3, q5, q6;
        AddChecked(X_BF, q, singular, options, result);
      }
    }
  }
  result.status = result.count > 0 ? IkStatus::kOk : IkStatus::kUnreachable;
  return result;
}

IkResult SolveTcpIk(const Eigen::Isometry3d& X_BT, double q6_current, const IkOptions& options) {
  return SolveIk(X_BT * TcpInFlange().inverse(), q6_current, options);
}

}  // namespace sortcell::robot
