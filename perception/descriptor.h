#pragma once
/// @file
/// Color-CVFH (paper section 2.2): [HSV 192 | CVFH 308] = 500 bins, and CVFH alone as the baseline.
///
/// Three kinds, all from the same two raw parts (so a dataset stores the parts once):
///  - "cvfh" (308): CVFH with each of its five blocks divided by the block's sum (each sums to 1).
///  - "color-cvfh" (500), the paper's raw form: [HSV counts | CVFH counts]. Block sums: S and V = the
///    object's point count, H = its chromatic point count, each CVFH block ~ its downsampled point count.
///  - "color-cvfh-norm" (500), the paper's "Color-CVFH (normalization)": every block divided by its
///    own sum, except hue, divided by the point count. S, V and each CVFH block sum to 1; H sums to the
///    object's chromatic fraction (0 for a grey object). Object size and sensor distance drop out.

#include <Eigen/Core>

#include <string>
#include <type_traits>
#include <vector>

#include "perception/cloud.h"
#include "perception/cvfh_descriptor.h"
#include "perception/feature_scaling.h"
#include "perception/hsv_histogram.h"

namespace sortcell::perception {

enum class DescriptorKind { kCvfh, kColorCvfh, kColorCvfhNorm };

/// "cvfh", "color-cvfh" or "color-cvfh-norm".
std::string DescriptorName(DescriptorKind kind);
/// Display name as in the paper's tables: "CVFH", "Color-CVFH", "Color-CVFH (normalization)".
std::string DescriptorTitle(DescriptorKind kind);
/// @throws std::invalid_argument "unknown descriptor '<name>' (expected cvfh, color-cvfh or color-cvfh-norm)".
DescriptorKind ParseDescriptorKind(const std::string& name);
/// 308 or 500.
int DescriptorSize(DescriptorKind kind);

/// The histograms a descriptor of `kind` is made of, in order: [hue | saturation | value] for the colour
/// kinds, then CVFH's five blocks (kCvfhBlocks). What the classifier's scaling scales as one.
std::vector<FeatureBlock> DescriptorBlocks(DescriptorKind kind);

struct DescriptorParams {
  HsvParams hsv;
  CvfhParams cvfh;
};

/// Calls `visit(key, field)` for every field of `params` (a DescriptorParams, const or not) with the
/// key it has in files ("hsv_min_saturation", "cvfh_voxel_leaf_m", ...), in a fixed order. The one list
/// of the parameters: the model file, the dataset manifest and SameDescriptorParams all go through
/// it, so a new field is added here and nowhere else.
template <typename Params, typename Visit>
void VisitDescriptorParams(Params& params, Visit&& visit) {
  static_assert(std::is_same_v<std::remove_const_t<Params>, DescriptorParams>);
  visit("hsv_min_saturation", params.hsv.min_saturation);
  visit("hsv_min_value", params.hsv.min_value);
  visit("cvfh_voxel_leaf_m", params.cvfh.voxel_leaf_m);
  visit("cvfh_normal_radius_m", params.cvfh.normal_radius_m);
  visit("cvfh_eps_angle_rad", params.cvfh.eps_angle_rad);
  visit("cvfh_curvature_threshold", params.cvfh.curvature_threshold);
  visit("cvfh_cluster_tolerance_m", params.cvfh.cluster_tolerance_m);
  visit("cvfh_min_region_points", params.cvfh.min_region_points);
  visit("cvfh_min_points", params.cvfh.min_points);
}

/// Whether two descriptor parameter sets give the same descriptors (every field equal).
bool SameDescriptorParams(const DescriptorParams& a, const DescriptorParams& b);

/// The two raw parts of an object's descriptor.
struct DescriptorParts {
  DescriptorStatus status = DescriptorStatus::kOk;  ///< CVFH's: whether the object could be described.
  std::string detail;                               ///< Why not, for a person (CVFH's detail); empty when ok.
  Eigen::VectorXf hsv;                              ///< 192 raw counts; empty when not ok.
  Eigen::VectorXf cvfh;  ///< 308, mean of the CVFH region histograms, raw counts; empty when not ok.
  int cvfh_regions = 0;
  double hsv_s = 0, normals_s = 0, cvfh_s = 0;  ///< Wall time of each step.
};

/// Both parts of the object's descriptor. CVFH comes first: when it cannot describe the object (too
/// few points, no histogram), the parts carry its status and detail, both vectors stay empty and the
/// HSV histogram is not computed.
/// @throws std::runtime_error as ComputeCvfh (a non-finite histogram from PCL).
DescriptorParts ComputeDescriptorParts(const Cloud& object_C, const DescriptorParams& params = {});

/// The descriptor of `kind` from the raw parts (see the file comment for each kind's blocks).
/// @throws std::invalid_argument "descriptor parts: <detail>" for parts whose status is not ok, or if
///         the parts do not have 192 and 308 bins.
Eigen::VectorXf AssembleDescriptor(const DescriptorParts& parts, DescriptorKind kind);

}  // namespace sortcell::perception
