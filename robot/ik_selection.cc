#include "robot/ik_selection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace sortcell::robot {

bool NearestCopyWithinLimits(const Joints& q, const Joints& q_current, const JointLimits& limits, Joints& out) {
  for (int i = 0; i < 6; ++i) {
    // Candidates q + 2 pi k around the current value; take the nearest one inside the limits.
    const double base = q[i] + 2.0 * M_PI * std::round((q_current[i] - q[i]) / (2.0 * M_PI));
    bool found = false;
    double best = 0;
    for (const double candidate : {base, base - 2.0 * M_PI, base + 2.0 * M_PI}) {
      if (candidate < limits.lower[i] || candidate > limits.upper[i]) continue;
      if (!found || std::abs(candidate - q_current[i]) < std::abs(best - q_current[i])) best = candidate;
      found = true;
    }
    if (!found) return false;
    out[i] = best;
  }
  return true;
}

bool LinksAboveTable(const Joints& q, double min_z) {
  const LinkFrames X = ForwardKinematicsAll(q);
  for (int i = 2; i <= 6; ++i) {
    if (X[i].translation().z() < min_z) return false;
  }
  return true;
}

std::optional<SelectedSolution> SelectNearest(const IkResult& ik, const Joints& q_current,
                                              const SelectionOptions& options) {
  // The links are checked nearest solution first, and only until one clears the table: forward kinematics
  // of every link is most of the selection's cost. A stable sort keeps the lower index first among equally
  // near solutions, as a scan for the strictly nearer one would.
  struct Candidate {
    int index;
    Joints q;
    double distance;
  };
  std::array<Candidate, std::tuple_size_v<decltype(ik.solutions)>> candidates;
  int count = 0;
  for (int k = 0; k < ik.count; ++k) {
    Joints q;
    if (!NearestCopyWithinLimits(ik.solutions[k].q, q_current, options.limits, q)) continue;
    candidates[count++] = {k, q, (q - q_current).norm()};
  }
  std::stable_sort(candidates.begin(), candidates.begin() + count,
                   [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  for (int i = 0; i < count; ++i) {
    if (LinksAboveTable(candidates[i].q, options.min_link_z))
      return SelectedSolution{candidates[i].index, candidates[i].q};
  }
  return std::nullopt;
}

}  // namespace sortcell::robot
