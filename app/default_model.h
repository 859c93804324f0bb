#pragma once
/// @file
/// The cached recognition model an episode uses when none is named: Color-CVFH (normalization)
/// trained on random cell scenes of the object set (the conditions the sorting cell sees), kept in
/// out/models/ of the data directory.

#include <filesystem>

#include "app/object_set.h"

namespace sortcell::app {

/// out/models/<set name>-color-cvfh-norm.model.json under DataDir().
std::filesystem::path DefaultModelPath(const ObjectSet& set);

/// The command that makes the default model, for error messages.
std::string DefaultModelHint(const ObjectSet& set);

/// Trains the default model of `set` if it is not there yet (150 random scenes, seed 0; about 20 s)
/// and returns its path. Written to a temporary file and renamed, so concurrent runs never
/// read a half-written model.
std::filesystem::path EnsureDefaultModel(const ObjectSet& set);

}  // namespace sortcell::app
