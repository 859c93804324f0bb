#pragma once
/// @file
/// Refusing a cell layout the robot cannot work in, with the reason: bins that overlap, stand off the
/// table or in the pick area, are too small or too large, or that the arm cannot place into; rules
/// that name a bin the layout lacks or leave a class of the model with nowhere to go.

#include <string>
#include <vector>

#include "cell/cell_layout.h"

namespace sortcell::cell {

/// Inside a bin, each side (m): the narrowest the gripper can lower an object into, the widest that
/// stays a bin on this table.
inline constexpr double kMinBinInside = 0.08;
inline constexpr double kMaxBinInside = 0.60;

/// @throws std::invalid_argument with the reason (naming the bins) if the bins cannot be used.
void CheckBins(const CellLayout& layout);
/// The part of CheckBins that depends on the table (a scene's may be smaller than the layout's default).
/// @throws std::invalid_argument naming the bin that stands off the table.
void CheckBinsOnTable(const CellLayout& layout);

/// @throws std::invalid_argument naming the class or bin if a rule names a bin the layout lacks,
///         reject_below is outside [0, 1], or the rules send one of `classes` nowhere.
void CheckRules(const CellLayout& layout, const std::vector<std::string>& classes);

}  // namespace sortcell::cell
