#pragma once
/// @file
/// Clusters that stop at concave creases: supervoxels (PCL's SupervoxelClustering) joined across convex
/// or flat connections and cut across concave ones (PCL's LCCP, Stein et al. 2014). Two objects that
/// touch meet in a concave crease (box on box, can beside box) and come apart; one object's own faces
/// meet convexly and stay together, whatever is printed on them. Colour only tightens the concavity
/// test: differently coloured supervoxels are cut at a shallower crease (colour_edge_concavity_deg) than
/// same-coloured ones (concavity_deg), so a print across a flat or convex face never splits an object.
/// Where supervoxels straddle two touching objects' contact, LCCP sees no crease between them: each
/// segment is then split where the voxels themselves show a concave crease that cuts it into two or
/// more large parts (split_at_creases).
/// The inside of a hollow object (a bowl, a mug, a pot) is concave, so LCCP cuts it into pieces: a
/// piece that lies mostly inside another cluster's volume (within its footprint on the supporting plane
/// and below its top) joins that cluster, and so does the inside seen over a wall's rim
/// (IsInsideOfHollow in the source); so does a small piece on top of a cluster's own top (a bottle's
/// neck and cap, cut off at the shoulder's crease); an object stacked on another is above the lower
/// one's top, about as large as it, and stays apart (a small object on a large one joins it); and so does
/// a small piece at the end of a long object lying on its side, on its axis (a lying bottle's neck).

#include <Eigen/Core>
#include <pcl/PointIndices.h>

#include <vector>

#include "perception/cloud.h"

namespace sortcell::perception {

struct ConvexClusteringParams {
  double voxel_m = 0.0075;    ///< Supervoxel voxel resolution.
  double seed_m = 0.03;       ///< Supervoxel seed resolution.
  double concavity_deg = 25;  ///< Connections more concave than this are cut.
  /// Colour edges: supervoxels whose mean colours differ by more than this CIE76 delta E (L*a*b*)...
  double colour_edge_delta_e = 10;
  /// ...are cut apart at a connection more concave than this (tighter than concavity_deg).
  double colour_edge_concavity_deg = 5;
  double colour_importance = 0;  ///< Supervoxels: weight of colour against space (1) and normals (normal_importance).
  double normal_importance = 4;
  /// The supervoxels' voxel normals computed here (SupervoxelVoxelNormals: PCL's up to rounding, faster)
  /// and handed to PCL; false: PCL computes them itself (kept to time the two in one run).
  bool own_voxel_normals = true;
  /// The supervoxels computed here (ExtractSupervoxels: PCL's bit for bit given those voxel normals, and the
  /// normals computed on the same grid), faster; false, or own_voxel_normals false: PCL's SupervoxelClustering
  /// (kept as the reference, and to time the two in one run).
  bool own_supervoxels = true;
  /// Where two objects touch, supervoxels (several voxels wide) can straddle the contact and hide its
  /// crease from LCCP. With split_at_creases, the crease is looked for at the voxels' own resolution: a
  /// voxel lies in a concave crease when at least crease_rising_neighbours of its neighbours within
  /// crease_radius_m rise above its tangent plane by more than crease_height_m and crease_deg; a segment
  /// whose other voxels fall into two or more connected parts (voxels within split_link_m) of at least
  /// split_min_voxels each is split into them (its crease voxels join the nearest part).
  bool split_at_creases = true;
  double crease_radius_m = 0.010;
  double crease_height_m = 0.003;
  double crease_deg = 20;
  int crease_rising_neighbours = 2;
  double split_link_m = 0.0075;
  int split_min_voxels = 60;
  /// Smaller and larger segments are dropped; SegmentObjects sets both from SegmentationParams.
  int min_cluster_voxels = 25, max_cluster_voxels = 20000;
  double inside_fraction = 0.8;   ///< A piece with this share of its voxels inside another cluster's volume joins it.
  double top_tolerance_m = 0.01;  ///< "Below the top": at most this much above the other cluster's highest voxel.
  /// The inside of a hollow object seen over its rim joins the wall it is seen over when:
  /// - the wall stands on the plane (its lowest voxel at most hollow_lift_m above it);
  /// - the wall is round: its footprint's median distance from the circle fitted through it is at most
  ///   round_wall_residual of the radius, and the radius at most round_wall_radius_factor times the
  ///   footprint's width (the near side of a round wall spans most of a half circle; a flat face fits
  ///   a circle of any size);
  /// - the piece lies beyond the wall from the camera, its top within rim_tolerance_m of the wall's (the
  ///   far rim), and all of it within the wall's circle plus rim_tolerance_m.
  double hollow_lift_m = 0.02;
  double rim_tolerance_m = 0.015;
  double round_wall_residual = 0.2;
  double round_wall_radius_factor = 0.75;
  /// A small piece (at most cap_fraction of another's voxels) that begins within cap_overlap_m below
  /// that other's top and stands over its footprint is its top (a bottle's neck and cap) and joins it.
  double cap_fraction = 0.25;
  double cap_overlap_m = 0.025;
  /// The same for a long object lying on its side (a footprint at least lying_elongation times as long
  /// as wide): a small piece no higher than it, its middle on its long axis up to neck_length_m beyond
  /// its end, is its neck and cap.
  double lying_elongation = 1.6;
  double neck_length_m = 0.06;
};

/// Clusters of `voxels` (camera frame) standing on the plane `plane_C` (n.p + d = 0, camera frame, n
/// towards the camera), as indices into `voxels`, largest first.
std::vector<pcl::PointIndices> ConvexClusters(const Cloud::Ptr& voxels, const Eigen::Vector4d& plane_C,
                                              const ConvexClusteringParams& params);

}  // namespace sortcell::perception
