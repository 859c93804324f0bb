#include "app/segment_labels.h"

#include <opencv2/core.hpp>

#include <algorithm>

namespace sortcell::app {

SegmentLabel LabelSegment(const cv::Mat& labels, const std::vector<int>& indices, int object_count) {
  std::vector<int> votes(object_count + 1, 0);
  for (int i : indices) ++votes[labels.at<uint16_t>(i / labels.cols, i % labels.cols)];
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

}  // namespace sortcell::app
