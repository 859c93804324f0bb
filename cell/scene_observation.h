#pragma once
/// @file
/// What the cell makes of one capture: the clusters on the table, each with a grasp footprint from
/// its visible points and, where it can be described, a category and the classifier's confidence.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cell/cell_layout.h"
#include "perception/cloud.h"
#include "perception/recognition_model.h"
#include "perception/segmentation.h"
#include "robot/grasp_planner.h"

namespace sortcell::cell {

/// The robot's calibration of its camera: the camera's pose as calibrated (not necessarily where it
/// truly is) and the empty cell as it saw it, for background subtraction.
struct CameraCalibration {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  perception::Cloud::Ptr background;  ///< Organized, same size as the captures; null: none.
};

/// One cluster of a capture.
struct Detection {
  perception::Segment segment;
  robot::ObjectFootprint footprint;
  /// Round (not a prism, pinched across the view): the fingers may close on it from any side
  /// (robot::FootprintEstimate).
  bool round = false;
  /// Lying on its side, long and low: pinched across its long axis only (robot::FootprintEstimate).
  bool lying = false;
  /// A prism pinched across its other pair of sides, where they fit the stroke.
  std::optional<robot::ObjectFootprint> turned;
  /// Partly hidden behind something nearer the camera: what shows is less than the object, and its
  /// footprint is not to be trusted (perception::OccludedEdgePixels).
  bool occluded = false;
  /// Where its points are, seen from above (world xy, m; every few points), and how high each is
  /// (world z, m; same order): what a neighbour's fingers and gripper body must keep clear of.
  std::vector<Eigen::Vector2d> p_W_xy;
  std::vector<double> p_W_z;
  std::optional<std::string> category;  ///< Empty when it could not be described (a fragment).
  double confidence = 0;
  /// The bin the cell's rules send it to (SortingPolicy; empty until then or when undescribed).
  std::string bin;
};

struct Observation {
  perception::SegmentationStatus status = perception::SegmentationStatus::kOk;
  std::vector<Detection> detections;  ///< Largest cluster first; empty unless status is kOk.
};

/// How the cell segments its captures: inside the layout's workspace box, into convex clusters, so that
/// touching objects come apart at the concave creases between them (Euclidean clusters would merge them).
perception::SegmentationParams CellSegmentation(const CellLayout& layout);

/// Segments `cloud` (organized, camera frame) within `params`' workspace, estimates each cluster's
/// footprint on the fitted table plane and classifies it. Clusters of fewer than 10 points are left
/// out; clusters too small to describe are kept without a category (neighbours, never picked).
/// An expected failure (no table in view, no valid point) is a status, not an exception.
/// @throws std::invalid_argument for misuse: a cloud that is not organized or empty, a background of
///         another size.
Observation ObserveScene(const perception::Cloud& cloud, const CameraCalibration& calibration,
                         const perception::SegmentationParams& params, const perception::RecognitionModel& model);

}  // namespace sortcell::cell
