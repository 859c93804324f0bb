#include "robot/ur5_ik.h"

#include <cmath>

#include "robot/ur5_dh.h"

namespace sortcell::robot {
namespace {

// A cosine this little past +-1 is rounding at a boundary (elbow straight, wrist aligned) and is
// clamped; anything further is out of reach.
constexpr double kCosineSlack = 1e-9;
constexpr double kDuplicateTolerance = 1e-7;  // rad, per joint, modulo 2 pi

// Into (-pi, pi]. The IK's angles lie within a few turns of zero, so shifting beats std::remainder
// (which costs ~20 ns and is called 48 times per solve).
double Wrap(double angle) {
  while (angle > M_PI) angle -= 2.0 * M_PI;
  while (angle <= -M_PI) angle += 2.0 * M_PI;
  return angle;
}

bool ClampCosine(double& c) {
  if (!(std::abs(c) <= 1.0 + kCosineSlack)) return false;  // also rejects NaN
  c = std::fmax(-1.0, std::fmin(1.0, c));
  return true;
}

// Both wrapped to (-pi, pi]: equal modulo 2 pi when their difference is near 0 or near +-2 pi.
bool SameModulo2Pi(const Joints& a, const Joints& b) {
  for (int i = 0; i < 6; ++i) {
    const double d = std::abs(a[i] - b[i]);
    if (std::fmin(d, 2.0 * M_PI - d) > kDuplicateTolerance) return false;
  }
  return true;
}

// R46 and p46 (frame 6 in frame 4) from the sines and cosines of q5, q6 (see FlangePose).
void WristTransform(double c5, double s5, double c6, double s6, Eigen::Matrix3d& R46, Eigen::Vector3d& p46) {
  using namespace ur5_lengths;    // NOLINT(google-build-using-namespace): the formulas' own names.
  R46 << c5 * c6, -c5 * s6, -s5,  //
      s5 * c6, -s5 * s6, c5,      //
      -s6, -c6, 0;
  p46 << -s5 * d6, c5 * d6, d5;
}

void AddChecked(const Eigen::Isometry3d& X_BF, const Joints& q_raw, bool singular, const IkOptions& options,
                IkResult& result) {
  if (!q_raw.allFinite()) return;
  Joints q;
  for (int i = 0; i < 6; ++i) q[i] = Wrap(q_raw[i]);
  for (int k = 0; k < result.count; ++k) {
    if (SameModulo2Pi(result.solutions[k].q, q)) return;
  }
  const Eigen::Isometry3d X = FlangePose(q);
  const double position_error = PositionError(X, X_BF);
  const double rotation_error = RotationError(X, X_BF);
  if (!(position_error <= options.accept_position && rotation_error <= options.accept_rotation)) return;
  result.solutions[result.count++] = {q, position_error, rotation_error, singular};
}

// Joints 5 and 6 of one wrist branch.
struct Wrist {
  double q5 = 0, q6 = 0, c5 = 1, s5 = 0, c6 = 1, s6 = 0;
  bool singular = false;
};

// From cos q5, the branch's sign of sin q5 and z1 seen in frame 6 (x6_z1, y6_z1); at the wrist
// singularity q6 stays where it is (q6_current). Sines and cosines from the geometry directly: cheaper and
// more exact than sin(acos(.)).
Wrist SolveWrist(double c5, double sign, double x6_z1, double y6_z1, double q6_current, const IkOptions& options) {
  Wrist w;
  w.c5 = c5;
  w.s5 = sign * std::sqrt(1.0 - c5 * c5);
  w.singular = std::abs(w.s5) < options.wrist_singular_sin;
  if (w.singular) {
    w.q5 = c5 > 0 ? 0.0 : M_PI;
    w.c5 = c5 > 0 ? 1.0 : -1.0;
    w.s5 = 0;
    w.q6 = q6_current;
    w.c6 = std::cos(w.q6);
    w.s6 = std::sin(w.q6);
    return w;
  }
  w.q5 = std::atan2(w.s5, w.c5);
  w.c6 = x6_z1 / w.s5;
  w.s6 = -y6_z1 / w.s5;
  const double norm = std::hypot(w.c6, w.s6);
  w.c6 /= norm;
  w.s6 /= norm;
  w.q6 = std::atan2(w.s6, w.c6);
  return w;
}

// Joints 2-4 for joint 1 and the wrist, both elbows, added to `result` where they check out: the planar
// chain of joints 2-4 in frame 1, X_14 = X_10 X_BF X_46^-1, written out because only its first column and
// its x, y are needed. R10 = Rx(-pi/2) Rz(-q1), p10 = (0, -d1, 0).
void AddElbowSolutions(const Eigen::Isometry3d& X_BF, double q1, const Wrist& w, const IkOptions& options,
                       IkResult& result) {
  using namespace ur5_lengths;  // NOLINT(google-build-using-namespace): the formulas' own names.
  const Eigen::Matrix3d& R = X_BF.linear();
  const Eigen::Vector3d& p = X_BF.translation();
  const double c1 = std::cos(q1), s1 = std::sin(q1);
  Eigen::Matrix3d R46;
  Eigen::Vector3d p46;
  WristTransform(w.c5, w.s5, w.c6, w.s6, R46, p46);
  const Eigen::Vector3d m0 = R * R46.row(0).transpose();  // first column of R_B4
  const Eigen::Vector3d p_B4 = p - R * (R46.transpose() * p46);
  const double q234 = std::atan2(m0.z(), c1 * m0.x() + s1 * m0.y());
  const double px = c1 * p_B4.x() + s1 * p_B4.y(), py = p_B4.z() - d1;
  double c3 = (px * px + py * py - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
  if (!ClampCosine(c3)) return;
  for (const double elbow : {1.0, -1.0}) {
    const double s3 = elbow * std::sqrt(1.0 - c3 * c3);
    const double q3 = std::atan2(s3, c3);
    // q2 = atan2(py, px) - atan2(a3 s3, a2 + a3 c3), as one atan2.
    const double k1 = a2 + a3 * c3, k2 = a3 * s3;
    const double q2 = std::atan2(py * k1 - px * k2, px * k1 + py * k2);
    Joints q;
    q << q1, q2, q3, q234 - q2 - q3, w.q5, w.q6;
    AddChecked(X_BF, q, w.singular, options, result);
  }
}

}  // namespace

IkResult SolveIk(const Eigen::Isometry3d& X_BF, double q6_current, const IkOptions& options) {
  using namespace ur5_lengths;  // NOLINT(google-build-using-namespace): the formulas' own names.
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
    const double x6_z1 = R(0, 0) * s1 - R(1, 0) * c1;  // z1 in frame 6 is (s5 c6, -s5 s6, c5)
    const double y6_z1 = R(0, 1) * s1 - R(1, 1) * c1;
    for (const double wrist : {1.0, -1.0}) {
      AddElbowSolutions(X_BF, q1, SolveWrist(c5, wrist, x6_z1, y6_z1, q6_current, options), options, result);
    }
  }
  result.status = result.count > 0 ? IkStatus::kOk : IkStatus::kUnreachable;
  return result;
}

IkResult SolveTcpIk(const Eigen::Isometry3d& X_BT, double q6_current, const IkOptions& options) {
  return SolveIk(X_BT * TcpInFlange().inverse(), q6_current, options);
}

}  // namespace sortcell::robot
