#pragma once
/// @file
/// The review image of a segmentation: the organized cloud's colour image with each segment tinted
/// in its own colour and labelled with its number.

#include <opencv2/core/mat.hpp>

#include <string>
#include <vector>

#include "perception/segmentation.h"

namespace sortcell::perception {

/// BGR image (CV_8UC3) of cloud.width x cloud.height; segment i is labelled labels[i] where given
/// (e.g. its category), else its number i.
/// @throws std::invalid_argument if the cloud is not organized.
cv::Mat SegmentOverlay(const Cloud& organized, const std::vector<Segment>& segments,
                       const std::vector<std::string>& labels = {});

}  // namespace sortcell::perception
