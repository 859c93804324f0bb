#pragma once
/// @file
/// PCL's CVFH (Aldoma et al. 2011) reduced to one 308-vector per object.
///
/// PCL 1.13 returns one VFH-shaped histogram per smooth region (K = 1..5, in point order). Each is laid
/// out [f1 45 | f2 45 | f3 45 | shape distribution 45 | viewpoint 128] and, in raw counts, every block
/// sums to about the point count. Reduction: the mean of the K region histograms. It keeps the block
/// sums, does not depend on the order PCL lists regions in, and every region counts (taking [0] would
/// pick an arbitrary one; the largest region alone throws the others away).

#include <Eigen/Core>

#include <array>
#include <string>

#include "perception/cloud.h"

namespace sortcell::perception {

inline constexpr int kCvfhBins = 308;
/// The five blocks of a CVFH histogram: first bin and size.
inline constexpr std::array<std::array<int, 2>, 5> kCvfhBlocks{{{0, 45}, {45, 45}, {90, 45}, {135, 45}, {180, 128}}};

/// CVFH parameters, all explicit. Lengths scale with the voxel leaf.
struct CvfhParams {
  double voxel_leaf_m = 0.005;         ///< Downsampling before normals and CVFH.
  double normal_radius_m = 0.015;      ///< Normal estimation radius (3 leaves).
  double eps_angle_rad = 0.13;         ///< Region growing: largest normal deviation (7.5 degrees).
  double curvature_threshold = 0.025;  ///< Region growing: seeds flatter than this (of the 1/3 maximum).
  double cluster_tolerance_m = 0.015;  ///< Region growing: neighbour distance.
  int min_region_points = 50;          ///< Smallest smooth region that gets its own histogram.
  int min_points = 30;                 ///< Fewer points after downsampling: DescriptorStatus::kTooFewPoints.
};

/// Expected ways an object cannot be described (a status, not an error: e.g. a small fragment).
enum class DescriptorStatus {
  kOk,
  kTooFewPoints,  ///< Fewer than `min_points` valid points after downsampling, or with a normal.
  kNoHistogram,   ///< PCL found no smooth region to make a histogram of.
};

/// "ok", "too_few_points", "no_histogram".
const char* ToString(DescriptorStatus status);

struct CvfhResult {
  DescriptorStatus status = DescriptorStatus::kOk;
  std::string detail;                ///< Why, for a person, when not ok (numbers included); empty when ok.
  Eigen::VectorXf histogram;         ///< 308 bins, raw counts, mean over the regions; empty when not ok.
  int regions = 0;                   ///< K, the number of region histograms PCL returned.
  int points = 0;                    ///< Points after NaN removal and downsampling.
  double normals_s = 0, cvfh_s = 0;  ///< Wall time of the two steps.
};

/// CVFH of one object's cloud, which must be in the camera frame (PCL's viewpoint is the origin).
/// A fresh PCL estimator is made on every call (a reused one accumulates state). An object that
/// cannot be described is an expected outcome: status kTooFewPoints (fewer than `min_points` valid
/// points, or points with a normal, remain) or kNoHistogram (PCL gives none), with `detail`.
/// @throws std::runtime_error if PCL returns a non-finite histogram (a fault in PCL, not in the input).
CvfhResult ComputeCvfh(const Cloud& object_C, const CvfhParams& params = {});

}  // namespace sortcell::perception
