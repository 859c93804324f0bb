#pragma once
/// @file
/// Where the repository's models/ and scenes/ live at run time.

#include <filesystem>
#include <string>

#include "sim/model.h"

namespace sortcell::files {

/// $SORTCELL_DATA_DIR, else the source tree this binary was built from.
std::string DataDir();

/// models/objects/textures under DataDir(): the object models' texture files.
std::filesystem::path ObjectTexturesDir();

/// Loads a scene file with the models' textures (sim::ModelTextures of models/ under DataDir()), which
/// object models name relative to scenes/ but MuJoCo then finds from a scene in any folder.
/// @throws std::invalid_argument as sim::Model::FromFile.
sim::Model LoadScene(const std::filesystem::path& scene);

}  // namespace sortcell::files
