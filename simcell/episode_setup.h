#pragma once
/// @file
/// Setting an episode's scene up: which objects of the set take part and where they stand.

#include <filesystem>
#include <optional>
#include <random>
#include <vector>

#include "files/cell_file.h"
#include "files/object_set.h"
#include "simcell/episode.h"
#include "sim/clutter_placement.h"
#include "sim/model.h"

namespace sortcell::simcell {

/// The episode's scene with the bins of `cell`: `scene` as it is when it holds every object of `set`
/// as a body; else the cell `scene` names (its table, camera and arm: the cell's models under
/// DataDir()) composed with the set's objects instead of the scene's own (sim::ComposeCell), so any
/// set, imported ones included, sorts in the default cell. Composed only for the default cell
/// (scenes/cell.xml).
/// @throws std::invalid_argument naming the scene and the objects it lacks for any other scene, or
///         as LoadCellScene.
sim::Model LoadEpisodeScene(const std::filesystem::path& scene, const files::ObjectSet& set,
                            const files::CellFile& cell);

/// The objects the model does not know (options.unknown_set), none when options.unknown_objects is 0.
/// @throws std::invalid_argument naming the option or set: a count without a set or beyond its size,
///         an object named as one of `set`'s.
files::ObjectSet LoadUnknownSet(const EpisodeOptions& options, const files::ObjectSet& set);
/// `set` with `unknown`'s objects after its own: every object the scene must hold.
files::ObjectSet WithUnknown(const files::ObjectSet& set, const files::ObjectSet& unknown);
/// `count` objects of `unknown` drawn at random (no draw from `rng` for none).
std::vector<files::ObjectSpec> ChooseUnknownObjects(const files::ObjectSet& unknown, int count, std::mt19937_64& rng);

/// How many objects the episode asks for: `options.objects`, or (0) all of the set, at most 6.
/// @throws std::invalid_argument for a count outside 1..set size.
int ObjectCount(const files::ObjectSet& set, const EpisodeOptions& options);

/// The objects of the episode: those placed by hand first, then the rest drawn at random from the
/// set, `options.objects` in all (0: all of the set, at most 6).
/// @throws std::invalid_argument for a count outside 1..set size, more placements than objects, an
///         object placed twice, or a placement naming an object the set lacks.
std::vector<files::ObjectSpec> ChooseObjects(const files::ObjectSet& set, const EpisodeOptions& options,
                                             std::mt19937_64& rng);

/// Table poses for objects of `shapes`: the given placements first (as given), the rest drawn at
/// random inside `area` as `placement` says (sim::SampleClutter: the training scenes' distribution).
/// @throws std::invalid_argument "--objects: N objects do not fit the table area ..." when no
///         arrangement is found, "--place: ..." for a placement lying that cannot lie.
std::vector<sim::TablePose> DrawPoses(const std::vector<ObjectPlacement>& placements,
                                      const std::vector<sim::ObjectShape>& shapes, const sim::PlacementArea& area,
                                      const sim::PlacementOptions& placement, std::mt19937_64& rng);
/// As DrawPoses, but empty when no arrangement is found.
/// @throws std::invalid_argument "--place: ..." for a placement lying that cannot lie.
std::optional<std::vector<sim::TablePose>> TryDrawPoses(const std::vector<ObjectPlacement>& placements,
                                                        const std::vector<sim::ObjectShape>& shapes,
                                                        const sim::PlacementArea& area,
                                                        const sim::PlacementOptions& placement, std::mt19937_64& rng);

}  // namespace sortcell::simcell
