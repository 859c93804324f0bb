#pragma once
// Random UR5 poses for property tests of motions.

#include <random>

#include "robot/ik_selection.h"

namespace sortcell::robot {

/// Uniform over the joints' useful ranges, redrawn until every link keeps `min_z` = 5 cm above the table.
inline Joints RandomPoseAboveTable(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  for (;;) {
    Joints q;
    q << 2 * M_PI * unit(rng), -M_PI * unit(rng), -2.8 + 5.6 * unit(rng), -M_PI + 2 * M_PI * unit(rng),
        -M_PI + 2 * M_PI * unit(rng), -M_PI + 2 * M_PI * unit(rng);
    if (LinksAboveTable(q, 0.05)) return q;
  }
}

}  // namespace sortcell::robot
