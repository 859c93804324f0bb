#include "cell/scene_observation.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "perception/occlusion.h"
#include "perception/recognition_model.h"
#include "robot/footprint_estimation.h"

namespace sortcell::cell {
namespace {

constexpr size_t kMinFootprintPoints = 10;  // robot::EstimateFootprint's minimum
constexpr size_t kOutlineStride = 4;        // Every 4th point (a few mm apart) outlines a neighbour.
// Edge pixels behind a nearer object that make a segment occluded: a few are noise at a contact.
constexpr int kOccludedEdgePixels = 8;

// The table's height under `p_W`, from the fitted plane n.p + d = 0 in the camera frame.
double TableHeightAt(const Eigen::Vector3d& p_W, const Eigen::Vector4d& plane_C, const Eigen::Isometry3d& X_WC) {
  const Eigen::Vector3d n_W = X_WC.linear() * plane_C.head<3>();
  const double d_W = plane_C[3] - n_W.dot(X_WC.translation());
  return std::abs(n_W.z()) > 1e-6 ? -(n_W.x() * p_W.x() + n_W.y() * p_W.y() + d_W) / n_W.z() : 0.0;
}

}  // namespace

perception::SegmentationParams CellSegmentation(const CellLayout& layout) {
  perception::SegmentationParams params;
  params.clustering = perception::SegmentationParams::Clustering::kConvex;
  params.workspace_min_W = layout.workspace_min_W;
  params.workspace_max_W = layout.workspace_max_W;
  return params;
}

Observation ObserveScene(const perception::Cloud& cloud, const CameraCalibration& calibration,
                         const perception::SegmentationParams& params, const perception::RecognitionModel& model) {
  // The cell's Kinect gives one point per pixel, and the occlusion check looks at pixels' neighbours.
  if (!cloud.isOrganized()) {
    throw std::invalid_argument("scene observation: the cloud is not organized (height " +
                                std::to_string(cloud.height) +
                                "): expected one point per pixel from the cell's Kinect");
  }
  Observation observation;
  perception::SegmentationResult segmented =
      perception::SegmentObjects(cloud, calibration.X_WC, calibration.background.get(), params);
  observation.status = segmented.status;
  if (segmented.status != perception::SegmentationStatus::kOk) return observation;
  const Eigen::Isometry3d& X_WC = calibration.X_WC;
  const std::vector<int> occluded_edge = perception::OccludedEdgePixels(cloud, segmented.segments);
  for (size_t s = 0; s < segmented.segments.size(); ++s) {
    perception::Segment& segment = segmented.segments[s];
    std::vector<Eigen::Vector3d> p_W;
    p_W.reserve(segment.cloud_C->size());
    for (const auto& p : segment.cloud_C->points) p_W.push_back(X_WC * Eigen::Vector3d(p.x, p.y, p.z));
    if (p_W.size() < kMinFootprintPoints) continue;
    Detection d;
    const double table_z = TableHeightAt(segment.centroid, segmented.plane_C, X_WC);
    const robot::FootprintEstimate estimate = robot::EstimateFootprint(p_W, X_WC.translation(), table_z);
    d.footprint = estimate.footprint;
    d.footprint.full_width_top_z = robot::FullWidthTop(p_W, d.footprint);
    // One pinched along its narrowest direction (too wide across the view) keeps it: turned, the
    // fingers would close on its width.
    d.round = !estimate.prism && estimate.across_view;
    d.lying = estimate.lying;
    d.turned = estimate.turned;
    if (d.turned) d.turned->full_width_top_z = d.footprint.full_width_top_z;
    d.occluded = occluded_edge[s] >= kOccludedEdgePixels;
    for (size_t k = 0; k < p_W.size(); k += kOutlineStride) {
      d.p_W_xy.push_back(p_W[k].head<2>());
      d.p_W_z.push_back(p_W[k].z());
    }
    // The reject rule is the sorting rules' (SortingPolicy: the reject bin).
    const perception::Recognition recognition = perception::Recognise(*segment.cloud_C, model);
    if (recognition.described()) {
      d.category = recognition.result.name;
      d.confidence = recognition.result.confidence;
    }
    d.segment = std::move(segment);
    observation.detections.push_back(std::move(d));
  }
  return observation;
}

}  // namespace sortcell::cell
