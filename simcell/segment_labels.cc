#include "simcell/segment_labels.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sortcell::simcell {

SegmentLabel LabelSegment(const cv::Mat& labels, const std::vector<int>& indices, int object_count) {
  if (labels.type() != CV_16UC1) throw std::invalid_argument("LabelSegment: the label image is not CV_16UC1");
  if (object_count < 0) throw std::invalid_argument("LabelSegment: negative object count");
  std::vector<int> votes(object_count + 1, 0);
  const int pixels = labels.rows * labels.cols;
  for (int i : indices) {
    if (i < 0 || i >= pixels) {
      throw std::invalid_argument("LabelSegment: pixel " + std::to_string(i) + " outside the " +
                                  std::to_string(labels.cols) + "x" + std::to_string(labels.rows) + " label image");
    }
    const int label = labels.at<uint16_t>(i / labels.cols, i % labels.cols);
    if (label > object_count) {
      throw std::invalid_argument("LabelSegment: label " + std::to_string(label) + " exceeds the object count " +
                                  std::to_string(object_count));
    }
    ++votes[label];
  }
  SegmentLabel out;
  out.label = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
  if (indices.empty()) return out;
  out.purity = static_cast<double>(votes[out.label]) / indices.size();
  if (out.label > 0) {
    const int mask = cv::countNonZero(labels == out.label);
    out.iou = static_cast<double>(votes[out.label]) / (mask + indices.size() - votes[out.label]);
  }
  return out;
}

}  // namespace sortcell::simcell
