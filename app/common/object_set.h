#pragma once
/// @file
/// Object sets: which object models exist and which category and instance each belongs to.
/// One YAML file per set (scenes/objects/*.yaml):
///   name: paper
///   objects:
///     - {name: bottle1, category: bottle, instance: bottle1, model: ../../models/objects/bottle1.inc.xml}
/// `model` is relative to the YAML file. Unknown keys are rejected.

#include <filesystem>
#include <string>
#include <vector>

namespace sortcell::app {

struct ObjectSpec {
  std::string name;      ///< The object's body name in the model (unique in the set).
  std::string category;  ///< Class label for category-level recognition and the bin it goes to.
  std::string instance;  ///< Class label for instance-level recognition.
  std::filesystem::path model;  ///< Absolute path of the object's MJCF fragment.
};

struct ObjectSet {
  std::string name;
  std::filesystem::path source;  ///< The YAML file.
  std::vector<ObjectSpec> objects;

  /// Distinct categories in order of first appearance.
  std::vector<std::string> Categories() const;
  /// The object called `name`. @throws std::invalid_argument naming the set and the object.
  const ObjectSpec& Find(const std::string& name) const;
};

/// @throws std::invalid_argument "object set '<file>': <what>" for a missing or malformed file, an
///         unknown or missing key, a value of the wrong type, a duplicate name or a missing model file.
ObjectSet LoadObjectSet(const std::filesystem::path& file);

/// A digest of what the set's objects look like: the content of their model files and of every file
/// in `texture_dir` (none if it does not exist). Captures record it, so data of other models is not
/// reused. Not a cryptographic hash: it tells versions of a set apart, nothing more.
std::string ObjectModelsDigest(const ObjectSet& set, const std::filesystem::path& texture_dir);

}  // namespace sortcell::app
