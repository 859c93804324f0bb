#include "robot/ik_selection.h"

#include <cmath>

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
  std::optional<SelectedSolution> best;
  double best_distance = 0;
  for (int k = 0; k < ik.count; ++k) {
    Joints q;
    if (!NearestCopyWithinLimits(ik.solutions[k].q, q_current, options.limits, q)) continue;
    if (!LinksAboveTable(q, options.min_link_z)) continue;
    const double distance = (q - q_current).norm();
    if (!best || distance < best_distance) {
      best = SelectedSolution{k, q};
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace sortcell::robot
