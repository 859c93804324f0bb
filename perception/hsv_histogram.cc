#include "perception/hsv_histogram.h"

#include <opencv2/core/mat.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace sortcell::perception {

Eigen::VectorXf HsvHistogram(const Cloud& cloud, const HsvParams& params) {
  Eigen::VectorXf histogram = Eigen::VectorXf::Zero(kHsvBins);
  cv::Mat rgb(1, static_cast<int>(cloud.size()), CV_8UC3);
  int n = 0;
  for (const PointT& p : cloud) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    rgb.at<cv::Vec3b>(0, n++) = cv::Vec3b(p.r, p.g, p.b);
  }
  if (n == 0) return histogram;
  cv::Mat hsv;
  cv::cvtColor(rgb.colRange(0, n), hsv, cv::COLOR_RGB2HSV);  // 8-bit: H 0..179, S and V 0..255.
  for (int i = 0; i < n; ++i) {
    const cv::Vec3b& c = hsv.at<cv::Vec3b>(0, i);
    if (c[1] >= params.min_saturation && c[2] >= params.min_value) histogram[c[0] / 2] += 1;
    histogram[kHueBins + c[1] * kSaturationBins / 256] += 1;
    histogram[kHueBins + kSaturationBins + c[2] * kValueBins / 256] += 1;
  }
  return histogram;
}

}  // namespace sortcell::perception
