#pragma once
/// @file
/// Object sets: which object models exist and which category and instance each belongs to.
/// One YAML file per set (scenes/objects/*.yaml):
///   name: paper
///   objects:
///     - {name: bottle1, category: bottle, instance: bottle1, model: ../../models/objects/bottle1.inc.xml}
///     - {name: mug, category: cup, instance: mug, urdf: ../../../shared/ycb/ycb/mug.urdf}
///     - {name: part, category: others, instance: part, mesh: part.stl, density: 1200, scale: 0.001}
/// Each object names exactly one of `model` (an MJCF fragment of ours), `urdf` (a one-link URDF) or `mesh`
/// (OBJ or STL, with `mass` or `density`), relative to the YAML file; `urdf` and `mesh` objects are
/// imported (assets/object_import.h) into the import cache and may say `mass`, `density`, `scale` and
/// `friction`. Unknown keys are rejected.
///
/// Optional `training_variety: [balls.yaml, ...]`: object sets of more members of this set's categories
/// (generated or imported), which the set's default recognition model also learns from, so that it
/// covers a category rather than the set's few instances. They are never placed in episodes. Their
/// objects must belong to the set's categories, their names must differ from the set's, and they may
/// not name a variety of their own.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "assets/object_import.h"

namespace sortcell::files {

struct ObjectSpec {
  std::string name;             ///< The object's body name in the model (unique in the set).
  std::string category;         ///< Class label for category-level recognition and the bin it goes to.
  std::string instance;         ///< Class label for instance-level recognition.
  std::filesystem::path model;  ///< Absolute path of the object's MJCF fragment (imported ones': in the cache).
  /// What the import did, for objects given as `urdf` or `mesh`.
  std::optional<assets::ImportReport> import;
};

struct ObjectSet {
  std::string name;
  std::filesystem::path source;  ///< The YAML file.
  std::vector<ObjectSpec> objects;
  /// The objects of the `training_variety` sets, for training only.
  std::vector<ObjectSpec> training_variety;

  /// Distinct categories in order of first appearance.
  std::vector<std::string> Categories() const;
  /// The object called `name`. @throws std::invalid_argument naming the set and the object.
  const ObjectSpec& Find(const std::string& name) const;
};

/// Imported objects are logged (what the import did, its warnings) when they are imported, not when
/// they come from the cache.
/// @throws std::invalid_argument "object set '<file>': <what>" for a missing or malformed file, an
///         unknown or missing key, a value of the wrong type, a duplicate name or a missing model file;
///         the importer's message (naming the URDF, mesh or texture) for an object that does not import.
ObjectSet LoadObjectSet(const std::filesystem::path& file);

/// Where imported objects are kept: $SORTCELL_IMPORT_CACHE when set; else the folder the build names
/// (compile definition SORTCELL_DEFAULT_IMPORT_CACHE, <build folder>/imports); else out/imports.
std::filesystem::path ImportCacheDir();

/// A digest of what the set's objects look like (its training variety's included): the content of their model files and
/// of every file in `texture_dir` (none if it does not exist). Captures record it, so data of other models is not
/// reused. Not a cryptographic hash: it tells versions of a set apart, nothing more.
std::string ObjectModelsDigest(const ObjectSet& set, const std::filesystem::path& texture_dir);

}  // namespace sortcell::files
