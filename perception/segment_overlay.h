#pragma once
/// @file
/// The review image of a segmentation: the organized cloud's colour image with each segment tinted
/// in its own colour and labelled with its number.

#include <opencv2/core/mat.hpp>

#include <vector>

#include "perception/segmentation.h"

namespace sortcell::perception {

/// BGR image (CV_8UC3) of cloud.width x cloud.height; segment i is numbered i.
/// @throws std::invalid_argument if the cloud is not organized.
cv::Mat SegmentOverlay(const Cloud& organized, const std::vector<Segment>& segments);

}  // namespace sortcell::perception
