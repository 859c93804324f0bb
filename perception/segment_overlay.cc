#include "perception/segment_overlay.h"

#include <opencv2/imgproc.hpp>

#include <stdexcept>
#include <string>

namespace sortcell::perception {

cv::Mat SegmentOverlay(const Cloud& organized, const std::vector<Segment>& segments,
                       const std::vector<std::string>& labels) {
  if (!organized.isOrganized()) throw std::invalid_argument("segment overlay: the cloud is not organized");
  const int w = static_cast<int>(organized.width), h = static_cast<int>(organized.height);
  cv::Mat image(h, w, CV_8UC3);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const PointT& p = organized.at(c, r);
      image.at<cv::Vec3b>(r, c) = cv::Vec3b(p.b, p.g, p.r);
    }
  }
  // Well separated hues (OpenCV's 0..179 scale), one per segment, cycling.
  for (size_t s = 0; s < segments.size(); ++s) {
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((s * 47) % 180, 255, 255)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b tint = bgr.at<cv::Vec3b>(0, 0);
    double sum_r = 0, sum_c = 0;
    for (int i : segments[s].indices) {
      cv::Vec3b& px = image.at<cv::Vec3b>(i / w, i % w);
      for (int k = 0; k < 3; ++k) px[k] = static_cast<uchar>((px[k] + tint[k]) / 2);
      sum_r += i / w;
      sum_c += i % w;
    }
    if (segments[s].indices.empty()) continue;
    const std::string text = s < labels.size() ? labels[s] : std::to_string(s);
    const cv::Point at(static_cast<int>(sum_c / segments[s].indices.size()) - 6,
                       static_cast<int>(sum_r / segments[s].indices.size()) + 6);
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  return image;
}

}  // namespace sortcell::perception
