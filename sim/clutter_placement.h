#pragma once
/// @file
/// Random scenes of objects that stand apart, touch, or lie: where a scene generator (episodes,
/// training scenes) puts each object. Footprints are the objects' convex outlines (sim/object_shape.h),
/// so objects placed to touch meet along their real sides, and nothing interpenetrates at the start.
/// Ground-truth tools, never used by the sorting loop.

#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "sim/object_placement.h"
#include "sim/object_shape.h"

namespace sortcell::sim {

enum class PlacementMode {
  kSparse,     ///< Every footprint the area's gap from every other (today's scenes).
  kDense,      ///< Objects may touch: each one placed against one placed before it (no gap).
  kClustered,  ///< Groups of 2-4 touching objects, the groups the area's gap apart.
};

/// The modes' spellings (CLI, sweep specs, metrics.json).
inline constexpr EnumNames<PlacementMode, 3> kPlacementModeNames{
    {{PlacementMode::kSparse, "sparse"}, {PlacementMode::kDense, "dense"}, {PlacementMode::kClustered, "clustered"}}};

/// "sparse", "dense", "clustered".
const char* ToString(PlacementMode mode);
/// The mode named `text`, or nullopt.
std::optional<PlacementMode> ParsePlacementMode(const std::string& text);

struct PlacementOptions {
  PlacementMode mode = PlacementMode::kSparse;
  /// Chance that an object which can lie (ObjectShape::lying: bottles, boxes, cans) is laid on its side.
  double lying_fraction = 0;
  /// Between footprints placed to touch (m): they meet without interpenetrating at the start.
  double contact_gap_m = 0.0005;
};

/// Poses for objects of `shapes` inside `area` (every outline inside the rectangle), the first
/// `fixed.size()` as given (upright or lying as their pose says; they keep the area's gap from the
/// drawn ones in sparse and clustered mode, and may be touched in dense mode). Up to
/// kPlacementArrangements fresh arrangements of up to `max_tries` draws per object; nullopt when the
/// objects do not fit.
/// @throws std::invalid_argument for more fixed poses than shapes or a lying fraction outside [0, 1].
std::optional<std::vector<TablePose>> SampleClutter(const std::vector<ObjectShape>& shapes,
                                                    const std::vector<TablePose>& fixed, const PlacementArea& area,
                                                    const PlacementOptions& options, std::mt19937_64& rng,
                                                    int max_tries = 500);

/// Sizes of the groups `count` objects form in clustered mode: 2-4 each (a lone object only when
/// count is 1), in a random order.
std::vector<int> ClusterSizes(int count, std::mt19937_64& rng);

}  // namespace sortcell::sim
