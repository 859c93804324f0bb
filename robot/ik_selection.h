#pragma once
/// @file
/// Choosing one IK solution: the one nearest to the current joints that the arm can actually take.

#include <optional>

#include "robot/ur5_ik.h"
#include "robot/ur5_limits.h"

namespace sortcell::robot {

struct SelectionOptions {
  JointLimits limits = Ur5JointLimits();
  /// Every D-H frame origin from the elbow (frame 2) to the flange (frame 6) must lie at least this
  /// high above the table (z = 0), so the links (radius <= 0.06 m) stay clear of it (m).
  double min_link_z = 0.06;
};

struct SelectedSolution {
  int index;  ///< Into IkResult::solutions.
  Joints q;   ///< That solution's 2 pi copy per joint nearest to q_current, inside the limits.
};

/// The solution nearest to `q_current` (Euclidean joint distance, each joint taking its 2 pi copy
/// nearest to the current value within the limits), among those inside the limits whose links stay
/// above the table; nullopt if none qualifies.
std::optional<SelectedSolution> SelectNearest(const IkResult& ik, const Joints& q_current,
                                              const SelectionOptions& options = {});

/// The 2 pi copy of `q` per joint nearest to `q_current` within `limits`; false if some joint has
/// no copy inside them.
bool NearestCopyWithinLimits(const Joints& q, const Joints& q_current, const JointLimits& limits, Joints& out);

/// True when every frame origin from the elbow to the flange is at least `min_z` high.
bool LinksAboveTable(const Joints& q, double min_z);

}  // namespace sortcell::robot
