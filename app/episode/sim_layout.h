#pragma once
/// @file
/// The cell's layout as the simulated cell builds it: cell::CellLayout's fixed knowledge with the
/// bins and the table read from the scene by name (bodies and sites "bin_<category>", geom "table_top").

#include <string>

#include <Eigen/Geometry>

#include "cell/cell_layout.h"
#include "sim/model.h"

namespace sortcell::app {

/// @throws std::invalid_argument naming the scene if it has no table geom "table_top" or a bin without
///         its floor site.
cell::CellLayout ReadCellLayout(const sim::Model& model);

/// The camera's pose in the world as the scene builds it (before any variation displaces it): what a
/// hand-eye calibration of the nominal cell gives the robot.
/// @throws std::invalid_argument naming the scene if it has no camera `camera`.
Eigen::Isometry3d NominalCameraPose(const sim::Model& model, const std::string& camera);

}  // namespace sortcell::app
