#pragma once
/// @file
/// Builds a cell scene (table, bins, Kinect, UR5 with gripper) holding a chosen list of object
/// models, e.g. an object set's, without writing files.

#include <filesystem>
#include <string>
#include <vector>

#include "sim/model.h"

namespace sortcell::sim {

/// The main MJCF text of a cell with the given object models (object fragments, see
/// models/objects/objects.inc.xml), plus the gripper tool slot, as MuJoCo virtual files.
/// `models_dir` is the repository's models/ folder. Paths are made absolute.
std::vector<Model::VirtualFile> ComposeCell(const std::filesystem::path& models_dir,
                                            const std::vector<std::filesystem::path>& object_models);

/// Compiles ComposeCell(...). `name` names the scene in errors (e.g. the object set file).
/// @throws std::invalid_argument naming a missing model file, or the scene with MuJoCo's message.
Model LoadComposedCell(const std::filesystem::path& models_dir,
                       const std::vector<std::filesystem::path>& object_models, const std::string& name);

}  // namespace sortcell::sim
