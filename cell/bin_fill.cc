#include "cell/bin_fill.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace sortcell::cell {
namespace {

constexpr double kCell = 0.02;            // Height map cells (m): ~100 Kinect points on a top face.
constexpr double kWallMargin = 0.012;     // Points this near a wall may be the wall's edge (m).
constexpr double kAboveFloor = 0.012;     // Lower points are the floor, with the depth noise (m).
constexpr double kBelowFloor = -0.01;     // Lower still: not in the bin (m).
constexpr double kTallest = 0.40;         // Higher points are not in the bin (the arm passing) (m).
constexpr int kTopRank = 3;               // A cell's height: its 3rd-highest point (stray pixels aside).
constexpr double kAboveContents = 0.015;  // Let go this far above what is already there (m).
constexpr double kArmMargin = 0.02;       // Points this near the arm's capsules are the arm (m).
constexpr double kLyingHalfWidth = 0.04;  // A lying bottle's radius and 5 mm (m): how far its axis stays from a wall.
constexpr double kAxisHalfWidth = 0.02;   // The band along a diagonal's axis (m).

// From p to the segment a-b, in 2D (a band's axis) or 3D (a capsule's).
template <typename Vector>
double DistanceToSegment(const Vector& p, const Vector& a, const Vector& b) {
  const Vector ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

bool OnArm(const Eigen::Vector3d& p_W, const CapsuleList& arm) {
  return std::any_of(arm.begin(), arm.end(),
                     [&](const Capsule& c) { return DistanceToSegment(p_W, c.a, c.b) < c.radius + kArmMargin; });
}

}  // namespace

BinFill::BinFill(const CellLayout& layout) : layout_(layout) {
  for (const auto& [name, bin] : layout.bins) {
    Map& map = maps_[name];
    map.half = bin.inner_half;
    map.nx = std::max(1, static_cast<int>(std::lround(2 * bin.inner_half.x() / kCell)));
    map.ny = std::max(1, static_cast<int>(std::lround(2 * bin.inner_half.y() / kCell)));
    map.height.assign(map.nx * map.ny, 0.0);
  }
}

Eigen::Vector2d BinFill::Map::CellCentre(int i, int j) const {
  return {-half.x() + (i + 0.5) * 2 * half.x() / nx, -half.y() + (j + 0.5) * 2 * half.y() / ny};
}

void BinFill::See(const perception::Cloud& cloud, const Eigen::Isometry3d& X_WC, const CapsuleList& arm) {
  std::map<std::string, std::vector<std::vector<double>>> seen;  // Per bin, per cell: point heights.
  for (const auto& [name, map] : maps_) seen[name].resize(map.height.size());
  for (const perception::PointT& point : cloud.points) {
    if (!std::isfinite(point.z)) continue;
    const Eigen::Vector3d p_W = X_WC * Eigen::Vector3d(point.x, point.y, point.z);
    for (const auto& [name, bin] : layout_.bins) {
      const Eigen::Vector3d d = p_W - bin.p_W_floor;
      const Eigen::Vector2d inside = bin.inner_half.array() - kWallMargin;
      if (std::abs(d.x()) > inside.x() || std::abs(d.y()) > inside.y() || d.z() < kBelowFloor || d.z() > kTallest)
        continue;
      if (!OnArm(p_W, arm)) {
        const Map& map = maps_.at(name);
        const int i = std::clamp(static_cast<int>((d.x() + map.half.x()) / (2 * map.half.x()) * map.nx), 0, map.nx - 1);
        const int j = std::clamp(static_cast<int>((d.y() + map.half.y()) / (2 * map.half.y()) * map.ny), 0, map.ny - 1);
        seen[name][i * map.ny + j].push_back(d.z() < kAboveFloor ? 0.0 : d.z());  // The floor: nothing on it.
      }
      break;  // Bins do not overlap.
    }
  }
  for (auto& [name, cells] : seen) {
    std::vector<double>& height = maps_.at(name).height;
    for (size_t c = 0; c < cells.size(); ++c) {
      std::vector<double>& z = cells[c];
      if (static_cast<int>(z.size()) < kTopRank) continue;
      std::nth_element(z.begin(), z.begin() + (kTopRank - 1), z.end(), std::greater<>());
      height[c] = z[kTopRank - 1];
    }
  }
}

bool BinFill::Under(const BinRelease& release, const Eigen::Vector2d& p) const {
  return DistanceToSegment(p, release.from, release.to) <= release.half_width;
}

void BinFill::Released(const std::string& bin, const BinRelease& release, double height) {
  // Let go, it comes to rest on what is under it.
  const double top = HighestUnder(bin, release) + height;
  Map& map = maps_.at(bin);
  for (int i = 0; i < map.nx; ++i) {
    for (int j = 0; j < map.ny; ++j) {
      double& cell = map.height[i * map.ny + j];
      if (Under(release, map.CellCentre(i, j))) cell = std::max(cell, top);
    }
  }
}

const BinFill::Map& BinFill::MapOf(const std::string& bin) const {
  const auto found = maps_.find(bin);
  if (found == maps_.end()) throw std::invalid_argument("cell layout: no bin '" + bin + "'");
  return found->second;
}

double BinFill::HighestUnder(const std::string& bin, const BinRelease& release) const {
  const Map& map = MapOf(bin);
  double highest = 0;
  for (int i = 0; i < map.nx; ++i) {
    for (int j = 0; j < map.ny; ++j) {
      if (Under(release, map.CellCentre(i, j))) highest = std::max(highest, map.height[i * map.ny + j]);
    }
  }
  return highest;
}

double BinFill::HighestIn(const std::string& bin) const {
  const std::vector<double>& height = MapOf(bin).height;
  return height.empty() ? 0.0 : *std::max_element(height.begin(), height.end());
}

BinRelease BinFill::Upright(const std::string& bin, int filled, double radius, double min_clearance,
                            const std::function<bool(const BinRelease&)>& placeable) const {
  MapOf(bin);  // Names an unknown bin first.
  if (layout_.bin_slots.empty()) throw std::invalid_argument("cell layout: no bin slots");
  const int n = static_cast<int>(layout_.bin_slots.size());
  auto at_slot = [&](int k) {
    BinRelease release;
    release.p_W_floor = BinSlot(layout_, bin, k);
    release.from = release.to = (release.p_W_floor - layout_.bins.at(bin).p_W_floor).head<2>();
    release.half_width = radius;
    release.yaw_step = layout_.place_yaw_step;
    return release;
  };
  // The least under it; heights within a centimetre count as the same: the layout's order decides
  // between them. Among the placeable slots if there are any (planned only for a slot that would be
  // chosen), else among all.
  std::optional<BinRelease> best, best_placeable;
  double best_height = 0, best_placeable_height = 0;
  for (int i = 0; i < n; ++i) {
    BinRelease candidate = at_slot((filled + i) % n);
    const double height = HighestUnder(bin, candidate);
    candidate.clearance = std::max(min_clearance, height + kAboveContents);
    if (placeable && (!best_placeable || height < best_placeable_height - 0.01) && placeable(candidate)) {
      best_placeable = candidate;
      best_placeable_height = height;
    }
    if (!best || height < best_height - 0.01) {
      best = candidate;
      best_height = height;
    }
  }
  return best_placeable ? *best_placeable : *best;
}

BinRelease BinFill::Lying(const std::string& bin) const {
  const Eigen::Vector2d half = MapOf(bin).half;  // Names an unknown bin first.
  const Eigen::Vector2d reach = half.array() - kLyingHalfWidth;
  // The object hangs along the TCP's x axis, (-sin yaw, cos yaw) for a top-down pinch at yaw: in a
  // square bin either diagonal, whichever the arm turns to more easily (in an oblong one, one
  // diagonal), let go above what is on both. (Choosing the
  // emptier one made the arm turn the wrist the long way, and a bottle grasped off its middle swung
  // out over a wall.) But when something stands above the walls on one diagonal (a bottle upright in
  // a corner slot) and not on the other, it goes along the other: let go above the standing bottle, a
  // lying one came to rest across its cap, above the bin.
  auto axis = [&](double sign) {
    BinRelease band;
    band.from = Eigen::Vector2d(-reach.x(), -sign * reach.y());
    band.to = Eigen::Vector2d(reach.x(), sign * reach.y());
    band.half_width = kAxisHalfWidth;
    return HighestUnder(bin, band);
  };
  // The diagonal along `sign` (its direction (reach.x, sign reach.y)) and its mirror through the middle.
  auto along = [&](double sign) { return std::atan2(-reach.x(), sign * reach.y()); };
  const double rising = axis(1), falling = axis(-1), above_walls = layout_.bin_wall_height + 0.01;
  BinRelease release;
  release.p_W_floor = layout_.bins.at(bin).p_W_floor;
  release.yaw_offset = along(-1);
  release.yaw_step = std::abs(reach.x() - reach.y()) < 1e-9 ? M_PI / 2 : M_PI;  // A square's both diagonals.
  double under = std::max(rising, falling);
  if (under + kAboveContents > above_walls && std::min(rising, falling) < under) {
    release.yaw_offset = along(rising < falling ? 1 : -1);
    release.yaw_step = M_PI;
    under = std::min(rising, falling);
  }
  release.clearance = std::max(above_walls, under + kAboveContents);
  // Where it ends is not known until a capture sees it: anywhere in the bin.
  release.half_width = 2 * half.maxCoeff();
  return release;
}

}  // namespace sortcell::cell
