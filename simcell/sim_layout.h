#pragma once
/// @file
/// The cell's layout as the simulated cell builds it: the cell file's bins and rules (files/cell_file.h)
/// with cell::CellLayout's fixed knowledge and the table read from the scene (geom "table_top"); and
/// scenes loaded with the cell file's bins.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "files/cell_file.h"
#include "cell/cell_layout.h"
#include "sim/model.h"

namespace sortcell::simcell {

/// Loads `scene` with the bins of `cell`: they replace what the scene includes as bins.inc.xml
/// (models/cell/bins.inc.xml in scenes/cell.xml).
/// @throws std::invalid_argument naming the scene if it does not compile, or if its bins are not the
///         cell file's (a scene with bins of its own, not included as bins.inc.xml).
sim::Model LoadCellScene(const std::filesystem::path& scene, const files::CellFile& cell);

/// @throws std::invalid_argument naming the scene and the cell file if the scene's bins (bodies and box
///         sites "bin_<name>") are not the cell file's, in name, place and size.
void CheckSceneBins(const sim::Model& model, const files::CellFile& cell);

/// The layout of `cell` in the scene: its bins and rules, the table from the scene.
/// @throws std::invalid_argument naming the scene if it has no table geom "table_top", or as CheckSceneBins.
cell::CellLayout ReadCellLayout(const sim::Model& model, const files::CellFile& cell);

/// One line per object (body name of `model`, the bin the rules send it to) that cannot lie flat in
/// its bin: as it stands or lies (sim::ObjectShape) it is longer than the bin's narrower inside side.
/// Empty: every bin holds what it receives.
std::vector<std::string> BinCapacityWarnings(const sim::Model& model, const cell::CellLayout& layout,
                                             const std::vector<std::pair<std::string, std::string>>& objects_and_bins);

/// The camera's pose in the world as the scene builds it (before any variation displaces it): what a
/// hand-eye calibration of the nominal cell gives the robot.
/// @throws std::invalid_argument naming the scene if it has no camera `camera`.
Eigen::Isometry3d NominalCameraPose(const sim::Model& model, const std::string& camera);

}  // namespace sortcell::simcell
