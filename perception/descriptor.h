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

#include "perception/cloud.h"
#include "perception/cvfh_descriptor.h"
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

struct DescriptorParams {
  HsvParams hsv;
  CvfhParams cvfh;
};

/// The two raw parts of an object's descriptor.
struct DescriptorParts {
  Eigen::VectorXf hsv;   ///< 192 raw counts.
  Eigen::VectorXf cvfh;  ///< 308, mean of the CVFH region histograms, raw counts.
  int cvfh_regions = 0;
  double hsv_s = 0, normals_s = 0, cvfh_s = 0;  ///< Wall time of each step.
};

/// @throws std::invalid_argument as ComputeCvfh (too few points).
DescriptorParts ComputeDescriptorParts(const Cloud& object_C, const DescriptorParams& params = {});

/// The descriptor of `kind` from the raw parts (see the file comment for each kind's blocks).
/// @throws std::invalid_argument if the parts do not have 192 and 308 bins.
Eigen::VectorXf AssembleDescriptor(const DescriptorParts& parts, DescriptorKind kind);

}  // namespace sortcell::perception
