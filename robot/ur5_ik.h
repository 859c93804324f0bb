#pragma once
/// @file
/// Analytic inverse kinematics of the UR5 (Hawkins 2013, "Analytic Inverse Kinematics for the
/// Universal Robots UR-5/UR-10 Arms"), all solutions, each checked by forward kinematics.
///
/// Poses are the flange's (D-H frame 6) in the Base frame (D-H frame 0), see robot/ur5_kinematics.h.
/// Geometric branches: shoulder left/right (q1), wrist up/down (q5), elbow up/down (q3): up to 8.
/// An unreachable pose is a status value (no exception, no NaN):
///   - the wrist centre inside the column of radius d4 = 0.10915 m around the base axis (q1 undefined),
///   - |cos q5| > 1 for both shoulder branches (the flange cannot face that way from there),
///   - the elbow cannot stretch or fold to the wrist (|cos q3| > 1).
/// Wrist singularity: where |sin q5| < IkOptions::wrist_singular_sin, joints 4 and 6 turn about the
/// same axis and only q4 + q6 is defined; q5 is snapped to 0 or pi and q6 is pinned to the caller's
/// current q6, so the arm does not spin its wrist for nothing.

#include <array>

#include <Eigen/Geometry>

#include "robot/ur5_kinematics.h"

namespace sortcell::robot {

enum class IkStatus { kOk, kUnreachable };

struct IkSolution {
  Joints q;               ///< Each joint wrapped to (-pi, pi].
  double position_error;  ///< |p_FK(q) - p_target| (m).
  double rotation_error;  ///< Angle of R_FK(q)^T R_target (rad).
  bool wrist_singular;    ///< q6 was pinned (|sin q5| below the threshold).
};

struct IkOptions {
  /// |sin q5| below this is the wrist singularity. In double precision, a pose that is exactly
  /// singular comes back with |sin q5| ~ 1e-8 (acos near 1 amplifies rounding); the band must be
  /// wider than that. 1e-6 keeps the pinned solution's error below ~3e-7 m and ~1e-6 rad
  /// (error ~ |sin q5| * |q6 - q6_true|) while any pose with |sin q5| >= 1e-6 is solved exactly
  /// (measured: tests/robot/ur5_ik_test.cc, WristNearSingular*).
  double wrist_singular_sin = 1e-6;
  /// A candidate whose FK misses the target by more than this is discarded (m, rad). Exact solutions
  /// are ~1e-14 off; the tolerance admits the pinned solutions in the singular band.
  double accept_position = 1e-5;
  double accept_rotation = 1e-5;
};

/// Up to 8 solutions, in a fixed-size array: no heap allocation, so the control loop may call it.
struct IkResult {
  IkStatus status = IkStatus::kUnreachable;
  int count = 0;
  std::array<IkSolution, 8> solutions;
};

/// All distinct solutions (modulo 2 pi) for the flange pose X_BF. `q6_current` is used only at the
/// wrist singularity. Never throws.
IkResult SolveIk(const Eigen::Isometry3d& X_BF, double q6_current = 0.0, const IkOptions& options = {});

/// Same for a TCP pose X_BT (X_BF = X_BT * X_FT^-1).
IkResult SolveTcpIk(const Eigen::Isometry3d& X_BT, double q6_current = 0.0, const IkOptions& options = {});

}  // namespace sortcell::robot
