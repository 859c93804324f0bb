#pragma once
/// @file
/// Wall-clock spans for the figures commands and timers report (never used in decisions).

#include <chrono>

namespace sortcell {

using WallClock = std::chrono::steady_clock;

/// Seconds of wall time since `start`.
inline double SecondsSince(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

}  // namespace sortcell
