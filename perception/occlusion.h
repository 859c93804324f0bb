#pragma once
/// @file
/// Which segments are partly hidden behind a nearer one. An object seen past the edge of another in
/// front of it shows less than its width, and a grasp planned from what shows would close on the
/// wrong place; its footprint is trustworthy only once the one in front has gone.

#include <vector>

#include "perception/cloud.h"
#include "perception/segmentation.h"

namespace sortcell::perception {

struct OcclusionParams {
  /// A neighbouring pixel this much nearer the camera (m) is in front of the segment.
  double min_depth_step = 0.02;
  /// Invalid pixels (the Kinect's shadow at a depth edge) skipped over to find that neighbour.
  int max_gap = 4;
};

/// For each segment, the number of its edge pixels whose neighbour across the edge (left, right, up,
/// down; past up to max_gap invalid pixels) is nearer the camera by min_depth_step: another segment,
/// or an unsegmented point. `cloud` is the organized cloud the segments' indices refer to.
/// @throws std::invalid_argument for an unorganized cloud or an index outside it.
std::vector<int> OccludedEdgePixels(const Cloud& cloud, const std::vector<Segment>& segments,
                                    const OcclusionParams& params = {});

}  // namespace sortcell::perception
