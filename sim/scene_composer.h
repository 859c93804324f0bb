#pragma once
/// @file
/// Builds a cell scene (table, bins, Kinect, UR5 with gripper) holding a chosen list of object
/// models, e.g. an object set's, without writing files.

#include <Eigen/Geometry>

#include <filesystem>
#include <string>
#include <vector>

#include "sim/model.h"

namespace sortcell::sim {

/// An extra fixed camera with the Kinect's field of view (e.g. a turntable elevation), aimed at a point.
struct CameraSpec {
  std::string name;
  Eigen::Vector3d p_W;       ///< Camera position in the world.
  Eigen::Vector3d target_W;  ///< Point on the optical axis; the image's x axis stays horizontal.
};

/// The main MJCF text of a cell with the given object models (object fragments, see
/// models/objects/objects.inc.xml) and extra cameras, plus the gripper tool slot, as MuJoCo virtual
/// files. `models_dir` is the repository's models/ folder. Paths are made absolute. `bins_xml`: the
/// bins' fragment (app::BinsXml); empty: the default cell's (models/cell/bins.inc.xml).
std::vector<Model::VirtualFile> ComposeCell(const std::filesystem::path& models_dir,
                                            const std::vector<std::filesystem::path>& object_models,
                                            const std::vector<CameraSpec>& cameras = {},
                                            const std::string& bins_xml = {});

/// The textures the models use, as virtual files found by their names: the objects' prints
/// (models_dir/objects/textures) and the gripper's calibration plate (models_dir/gripper/textures).
std::vector<Model::VirtualFile> ModelTextures(const std::filesystem::path& models_dir);

/// Compiles ComposeCell(...) with ModelTextures(models_dir).
/// `name` names the scene in errors (e.g. the object set file).
/// @throws std::invalid_argument naming a missing model file, or the scene with MuJoCo's message.
Model LoadComposedCell(const std::filesystem::path& models_dir, const std::vector<std::filesystem::path>& object_models,
                       const std::string& name, const std::vector<CameraSpec>& cameras = {},
                       const std::string& bins_xml = {});

}  // namespace sortcell::sim
