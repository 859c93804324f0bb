#pragma once
/// @file
/// A view sheet: rows of object views drawn from their clouds as the camera saw them, each row titled,
/// to set a dataset's views beside another's (e.g. real Kinect views beside simulated captures of the
/// same category: `sortcell views`).

#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "perception/cloud.h"
#include "training/dataset.h"

namespace sortcell::training {

/// One row of a sheet: its title and the views shown in it (object points in the camera frame).
struct ViewSheetRow {
  std::string title;
  std::vector<perception::Cloud::ConstPtr> views_C;
};

/// The indices of `count` samples of `d` whose category or instance is `label`, spread evenly over
/// them in manifest order (all of them when fewer, or when `count` is 0 or less). Only samples through
/// the sensor as modelled (`fits_familiarity`) when the label has any: not a recipe's widened twin.
/// @throws std::invalid_argument "<where>: no sample is labelled '<label>' ..." when none is.
std::vector<int> SpreadSamples(const Dataset& d, const std::string& label, int count, const std::string& where);

/// Draws the rows: a title column as wide as the longest title, then one square tile of `tile_px` per
/// view. Each view is projected through a pinhole at the camera's origin, fitted to its tile, nearest
/// point in front, every point as large as the view's point spacing so that a sparse view reads as a
/// surface. Points that are not finite or nearer than 1 cm are left out; a view left with none (or a
/// null one) leaves its tile blank, and one with no extent (one point) is a dot in its middle.
/// @throws std::invalid_argument for no rows or a tile smaller than 16 px.
cv::Mat DrawViewSheet(const std::vector<ViewSheetRow>& rows, int tile_px);

}  // namespace sortcell::training
