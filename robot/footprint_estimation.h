#pragma once
/// @file
/// A grasp footprint from what a depth camera sees of an object standing on the table: its points in
/// the world frame. The camera sees the front and the top, never the back. Across the line of sight
/// the visible points span the object's full width; along it only the front is certain. So the
/// fingers close across the line of sight whenever the object fits the stroke that way, centred on
/// the visible extent there; along the line of sight the hidden back is completed by assuming the
/// object is at least as deep as it is wide (round objects), or as deep as seen (prisms, whose top
/// face shows their depth). A prism (box, cup: its top face spans its width) that is clearly
/// narrower in another direction is pinched there instead, centred on its visible extents, as is
/// anything too wide for the stroke across the line of sight.
///
/// An object lying on its side (a bottle, a can: long, and low for its length) is pinched across its
/// long axis (the principal axes of its points on the table), in the middle of the stretch along the
/// axis where it stands at its full height (a bottle's body, not its neck: the thick part, near its
/// mass's centre), its width across the axis at least its height (a round section), the hidden far
/// side completed as above.
///
/// Why not the centroid of the points (the paper's grasp point): it lies on the visible half, biased
/// towards the camera by up to a radius (~2 cm for a bottle), more than the finger clearance.

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "robot/grasp_planner.h"

namespace sortcell::robot {

struct FootprintOptions {
  /// Widest object the fingers may close on across the line of sight (m): the stroke less clearance.
  double max_width = 0.100;
  /// Extents use these quantiles of the projected points, so a few stray points do not widen them.
  double low_quantile = 0.01;
  double high_quantile = 0.99;
  /// Points this close to the highest point form the top face (m).
  double top_slice = 0.010;
  /// A top face at least this fraction of the object's width across the line of sight makes a prism.
  double prism_ratio = 0.8;
  /// A prism is pinched across the line of sight unless that is more than this times its narrowest width.
  double across_preference = 1.1;
  /// Candidate pinch directions (rad step).
  double yaw_step = 2.5 * 3.14159265358979323846 / 180;
  /// Lying: at least this many times as long as it is wide and as it is high.
  double lying_elongation = 1.6;
};

struct FootprintEstimate {
  ObjectFootprint footprint;
  bool across_view = true;  ///< Fingers close across the line of sight (else along the narrowest direction).
  bool prism = false;       ///< The top face spans the object's width.
  bool lying = false;       ///< Long and low: pinched across its long axis, never turned.
  /// A prism pinched the other way (a quarter turn, across its other pair of sides) where that fits
  /// the stroke: a second grasp when a neighbour stands in the first one's way.
  std::optional<ObjectFootprint> turned;
};

/// The highest height (world z, m) below which `object` is still nearly as wide as its footprint: the
/// lower edge of the highest 1 cm band of its points `p_W` (world) reaching `fraction` of its half-width
/// from its centre; -infinity if none does.
double FullWidthTop(const std::vector<Eigen::Vector3d>& p_W, const ObjectFootprint& object, double fraction = 0.85);

/// @param p_W        The object's points in the world frame (z up, table at `table_z`).
/// @param p_W_camera The camera's position in the world.
/// @throws std::invalid_argument if fewer than 10 points are given or the camera stands above the object.
FootprintEstimate EstimateFootprint(const std::vector<Eigen::Vector3d>& p_W, const Eigen::Vector3d& p_W_camera,
                                    double table_z, const FootprintOptions& options = {});

}  // namespace sortcell::robot
