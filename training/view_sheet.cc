#include "training/view_sheet.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sortcell::training {
namespace {

constexpr int kMarginPx = 4;
// Points nearer than this are no object's (a sensor sees nothing so close) and would blow up x/z.
constexpr float kNearestDepthM = 0.01f;
const int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.45;
const cv::Scalar kBackground(235, 235, 235);
// The share of its bounding box an object's view fills (a disc fills pi/4 of its square): the view's
// point spacing is estimated from its count and its box's area.
constexpr double kFilledShare = 0.785;

struct ProjectedPoint {
  cv::Point2d uv;  // x/z, y/z: the pinhole image at unit focal length.
  float depth = 0;
  cv::Vec3b bgr;
};

std::vector<ProjectedPoint> Project(const perception::Cloud& view_C, cv::Rect2d& box) {
  std::vector<ProjectedPoint> points;
  double u0 = std::numeric_limits<double>::max(), v0 = u0, u1 = -u0, v1 = -u0;
  for (const perception::PointT& p : view_C) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || p.z < kNearestDepthM) continue;
    const cv::Point2d uv(static_cast<double>(p.x) / p.z, static_cast<double>(p.y) / p.z);
    points.push_back({uv, p.z, cv::Vec3b(p.b, p.g, p.r)});
    u0 = std::min(u0, uv.x), u1 = std::max(u1, uv.x), v0 = std::min(v0, uv.y), v1 = std::max(v1, uv.y);
  }
  if (!points.empty()) box = cv::Rect2d(u0, v0, u1 - u0, v1 - v0);
  return points;
}

// One view fitted into `tile` (a square of the sheet), its nearest point in front in each pixel.
void DrawView(const perception::Cloud& view_C, cv::Mat tile) {
  cv::Rect2d box;
  const std::vector<ProjectedPoint> points = Project(view_C, box);
  if (points.empty()) return;
  // A view of one point, or of points on one ray, has no extent: it is drawn as a dot in the middle.
  const double extent = std::max({box.width, box.height, 1e-9});
  const double scale = (tile.cols - 2 * kMarginPx) / extent;
  const double spacing = std::sqrt(kFilledShare * box.area() / static_cast<double>(points.size()));
  const int dot = std::clamp(static_cast<int>(std::ceil(scale * spacing)), 1, tile.cols);
  const cv::Point2d offset((tile.cols - scale * box.width) / 2, (tile.rows - scale * box.height) / 2);
  cv::Mat nearest(tile.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::max()));
  for (const ProjectedPoint& p : points) {
    const int u = static_cast<int>(offset.x + scale * (p.uv.x - box.x)) - dot / 2;
    const int v = static_cast<int>(offset.y + scale * (p.uv.y - box.y)) - dot / 2;
    for (int y = std::max(v, 0); y < std::min(v + dot, tile.rows); ++y) {
      for (int x = std::max(u, 0); x < std::min(u + dot, tile.cols); ++x) {
        if (p.depth >= nearest.at<float>(y, x)) continue;
        nearest.at<float>(y, x) = p.depth;
        tile.at<cv::Vec3b>(y, x) = p.bgr;
      }
    }
  }
}

}  // namespace

std::vector<int> SpreadSamples(const Dataset& d, const std::string& label, int count, const std::string& where) {
  std::vector<int> labelled;
  for (size_t i = 0; i < d.samples.size(); ++i) {
    if (d.samples[i].category == label || d.samples[i].instance == label) labelled.push_back(static_cast<int>(i));
  }
  // The views through the sensor as modelled, when the label has any: a recipe's widened twin
  // (classifier-only, colours jittered) would show colours the Kinect model does not give.
  std::vector<int> as_modelled;
  for (int i : labelled) {
    if (d.samples[i].fits_familiarity) as_modelled.push_back(i);
  }
  if (!as_modelled.empty()) labelled = std::move(as_modelled);
  if (labelled.empty()) {
    throw std::invalid_argument(where + ": no sample is labelled '" + label +
                                "' (expected one of its categories or instances)");
  }
  if (count <= 0 || static_cast<size_t>(count) >= labelled.size()) return labelled;
  std::vector<int> spread;
  for (int k = 0; k < count; ++k) spread.push_back(labelled[(2 * k + 1) * labelled.size() / (2 * count)]);
  return spread;
}

cv::Mat DrawViewSheet(const std::vector<ViewSheetRow>& rows, int tile_px) {
  if (rows.empty()) throw std::invalid_argument("view sheet: no rows");
  if (tile_px < 16) throw std::invalid_argument("view sheet: tiles of " + std::to_string(tile_px) + " px (16 or more)");
  size_t columns = 1;
  int title_width = 0, baseline = 0;
  for (const ViewSheetRow& row : rows) {
    columns = std::max(columns, row.views_C.size());
    title_width = std::max(title_width, cv::getTextSize(row.title, kFont, kFontScale, 1, &baseline).width);
  }
  const int first_tile = title_width + 4 * kMarginPx;
  cv::Mat sheet(static_cast<int>(rows.size()) * tile_px, first_tile + static_cast<int>(columns) * tile_px, CV_8UC3,
                kBackground);
  for (size_t r = 0; r < rows.size(); ++r) {
    const int top = static_cast<int>(r) * tile_px;
    cv::putText(sheet, rows[r].title, cv::Point(2 * kMarginPx, top + tile_px / 2 + 5), kFont, kFontScale,
                cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
    for (size_t c = 0; c < rows[r].views_C.size(); ++c) {
      const cv::Rect cell(first_tile + static_cast<int>(c) * tile_px, top, tile_px, tile_px);
      if (rows[r].views_C[c]) DrawView(*rows[r].views_C[c], sheet(cell));
    }
  }
  return sheet;
}

}  // namespace sortcell::training
