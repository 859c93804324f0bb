#pragma once
/// @file
/// Deterministic random streams: one std::mt19937_64 per episode, derived from (seed, episode index).

#include <cstdint>
#include <random>

namespace sortcell {

/// The generator for episode `index` of a run seeded with `seed`. Streams of different episodes
/// are decorrelated through std::seed_seq; the same pair always gives the same stream.
inline std::mt19937_64 EpisodeRng(uint64_t seed, uint64_t index) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), static_cast<uint32_t>(index),
                    static_cast<uint32_t>(index >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace sortcell
