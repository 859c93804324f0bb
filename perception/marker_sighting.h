#pragma once
/// @file
/// An ArUco marker (OpenCV's 4x4_50 dictionary) seen in an organized RGB-D cloud: its corners in the
/// colour image (sub-pixel), its plane from the depth points on it, and its centre where the ray
/// through the centre of the corners meets that plane. The colour image fixes the centre across the
/// view to a fraction of a pixel; the plane, fitted to hundreds of points, fixes it along the view
/// far better than one Kinect depth can.

#include <array>
#include <optional>

#include <Eigen/Core>

#include "perception/cloud.h"
#include "perception/cloud_pinhole.h"

namespace sortcell::perception {

struct MarkerSighting {
  Eigen::Vector3d p_C_centre = Eigen::Vector3d::Zero();  ///< The marker's centre, camera frame (m).
  Eigen::Vector3d n_C = Eigen::Vector3d::Zero();         ///< Its plane's normal, towards the camera.
  std::array<Eigen::Vector2d, 4> corners_px{};           ///< Image corners, the dictionary's order.
  int plane_points = 0;                                  ///< Depth points the plane was fitted to.
  double plane_rms_m = 0;                                ///< Their distance from it, RMS (m).
};

struct MarkerSightingParams {
  int min_plane_points = 40;
  /// The plane is fitted to the points inside the corners' quadrilateral scaled by this factor about
  /// its centre: inside the black square, clear of its edges (where the Kinect's lateral noise mixes
  /// in what is behind or in front of the plate).
  double plane_region_scale = 0.9;
};

/// The marker `id` in `cloud` (organized, camera frame, colour registered), seen through `pinhole`;
/// empty when it is not found or too few valid depth points lie on it.
/// @throws std::invalid_argument for an unorganized cloud or an id outside the dictionary (0..49).
std::optional<MarkerSighting> FindMarker(const Cloud& cloud, const Pinhole& pinhole, int id,
                                         const MarkerSightingParams& params = {});

}  // namespace sortcell::perception
