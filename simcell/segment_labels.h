#pragma once
/// @file
/// Which simulated object a segment shows, from the camera's ground-truth label image (scoring and
/// training labels only; the sorting loop never sees it).

#include <opencv2/core/mat.hpp>

#include <vector>

namespace sortcell::simcell {

struct SegmentLabel {
  int label = 0;      ///< The label most of the segment's pixels carry (0 = no object).
  double purity = 0;  ///< Fraction of the segment's pixels with that label.
  double iou = 0;     ///< Intersection over union of the segment and that object's mask (0 for label 0).
};

/// `labels`: CV_16UC1 label image (sim::KinectFrame::labels); `indices`: the segment's pixels
/// (row * cols + col); `object_count`: the largest label.
/// @throws std::invalid_argument for a label image that is not CV_16UC1, a pixel outside it, or a label
///         above `object_count`.
SegmentLabel LabelSegment(const cv::Mat& labels, const std::vector<int>& indices, int object_count);

}  // namespace sortcell::simcell
