#include "perception/occlusion.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sortcell::perception {
namespace {

constexpr int kUnlabelled = -1;

// Whether the first valid pixel from `index` in direction (dr, dc), outside segment `label`, is nearer
// the camera than `depth` by the step.
bool NearerAcrossEdge(const Cloud& cloud, const std::vector<int>& labels, int index, int dr, int dc, int label,
                      const OcclusionParams& params) {
  const int width = static_cast<int>(cloud.width), height = static_cast<int>(cloud.height);
  const int row = index / width, col = index % width;
  const double depth = cloud.points[index].z;
  for (int step = 1; step <= params.max_gap + 1; ++step) {
    const int r = row + dr * step, c = col + dc * step;
    if (r < 0 || r >= height || c < 0 || c >= width) return false;
    const int j = r * width + c;
    if (labels[j] == label) return false;  // Not an edge that way.
    const PointT& p = cloud.points[j];
    if (!std::isfinite(p.z)) continue;  // The depth edge's shadow: look past it.
    return p.z < depth - params.min_depth_step;
  }
  return false;
}

}  // namespace

std::vector<int> OccludedEdgePixels(const Cloud& cloud, const std::vector<Segment>& segments,
                                    const OcclusionParams& params) {
  if (!cloud.isOrganized()) throw std::invalid_argument("OccludedEdgePixels: the cloud is not organized");
  std::vector<int> labels(cloud.size(), kUnlabelled);
  for (size_t s = 0; s < segments.size(); ++s) {
    for (int index : segments[s].indices) {
      if (index < 0 || index >= static_cast<int>(cloud.size())) {
        throw std::invalid_argument("OccludedEdgePixels: segment " + std::to_string(s) + " has pixel " +
                                    std::to_string(index) + " outside the " + std::to_string(cloud.width) + "x" +
                                    std::to_string(cloud.height) + " cloud");
      }
      labels[index] = static_cast<int>(s);
    }
  }
  std::vector<int> occluded(segments.size(), 0);
  constexpr int kDirections[4][2] = {{0, 1}, {0, -1}, {1, 0}, {-1, 0}};
  for (size_t s = 0; s < segments.size(); ++s) {
    for (int index : segments[s].indices) {
      if (!std::isfinite(cloud.points[index].z)) continue;
      for (const auto& d : kDirections) {
        if (NearerAcrossEdge(cloud, labels, index, d[0], d[1], static_cast<int>(s), params)) {
          ++occluded[s];
          break;
        }
      }
    }
  }
  return occluded;
}

}  // namespace sortcell::perception
