#pragma once
/// @file
/// Wall-clock spans for the figures commands report (never used in decisions).

#include <chrono>

#include "perception/seconds_since.h"

namespace sortcell::app {

using WallClock = std::chrono::steady_clock;

/// Seconds of wall time since a WallClock time point (one definition, perception's: the lowest layer).
using perception::SecondsSince;

}  // namespace sortcell::app
