#pragma once
/// @file
/// The UR5 (CB-series) Denavit-Hartenberg table, the arm's kinematic constants in code (from the URDF).
/// Frame 0 is the UR controller's Base frame (= the world frame W of the cell), frame 6 the tool
/// flange. Standard D-H: T_{i-1,i} = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i), theta_i = q_i (no offsets).

#include <array>
#include <cmath>

#include "sortcell/ur5_urdf.h"

namespace sortcell::robot {

struct DhRow {
  double d;      ///< m, along z_{i-1}
  double a;      ///< m, along x_i
  double alpha;  ///< rad, about x_i
};

/// The rows from models/ur5/ur5.urdf's joints' origins (ur5_urdf.h, generated at build time by
/// models/tools/ur5_urdf_header.py).
constexpr std::array<DhRow, 6> Ur5DhFromUrdf() {
  std::array<DhRow, 6> rows{};
  for (size_t i = 0; i < rows.size(); ++i) rows[i] = {ur5_urdf::kDhD[i], ur5_urdf::kDhA[i], ur5_urdf::kDhAlpha[i]};
  return rows;
}

/// UR5 CB-series (not UR5e).
inline constexpr std::array<DhRow, 6> kUr5Dh = Ur5DhFromUrdf();

/// The table's lengths by the names the closed-form FK and IK use (m).
namespace ur5_lengths {
inline constexpr double d1 = kUr5Dh[0].d, a2 = kUr5Dh[1].a, a3 = kUr5Dh[2].a;
inline constexpr double d4 = kUr5Dh[3].d, d5 = kUr5Dh[4].d, d6 = kUr5Dh[5].d;
}  // namespace ur5_lengths

}  // namespace sortcell::robot
