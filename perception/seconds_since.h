#pragma once
/// @file
/// Wall-clock spans for the timings perception reports (never used in decisions).

#include <chrono>

namespace sortcell::perception {

/// Seconds of wall time since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace sortcell::perception
