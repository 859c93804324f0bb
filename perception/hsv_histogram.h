#pragma once
/// @file
/// The paper's global colour histogram (section 2.2): OpenCV 8-bit HSV, 90 hue bins of 2 (H in
/// 0..179), 51 saturation and 51 value bins (index = v * 51 / 256), 192 bins in all.
///
/// Achromatic pixels: hue is undefined for grey, white and black (OpenCV gives them H = 0, which
/// would pile them into the red bin). A pixel whose saturation or value is below the thresholds
/// counts in the S and V blocks but not in the H block. So, in raw counts, the S and V blocks each sum
/// to the number of points and the H block to the number of chromatic points; a grey object has an
/// empty hue block.

#include <Eigen/Core>

#include "perception/cloud.h"

namespace sortcell::perception {

inline constexpr int kHueBins = 90;
inline constexpr int kSaturationBins = 51;
inline constexpr int kValueBins = 51;
inline constexpr int kHsvBins = kHueBins + kSaturationBins + kValueBins;  // 192

struct HsvParams {
  int min_saturation = 26;  ///< Below (of 255): achromatic, no hue.
  int min_value = 26;       ///< Below (of 255): too dark for a hue.
};

/// Raw counts [H 90 | S 51 | V 51] over the cloud's points with finite coordinates.
Eigen::VectorXf HsvHistogram(const Cloud& cloud, const HsvParams& params = {});

}  // namespace sortcell::perception
