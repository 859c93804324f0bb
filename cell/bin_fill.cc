#include "cell/bin_fill.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sortcell::cell {
namespace {

constexpr double kSlotHalfWidth = 0.05;   // A slot's square: a quadrant of the 0.2 m bin (m).
constexpr double kWallMargin = 0.015;     // Points this near a wall may be the wall's edge (m).
constexpr double kAboveFloor = 0.012;     // Lower points are the floor, with the depth noise (m).
constexpr double kTallest = 0.40;         // Higher points are not in the bin (the arm passing) (m).
constexpr int kTopRank = 8;               // The slot's height: its 8th-highest point (stray pixels aside).
constexpr double kAboveContents = 0.015;  // Let go this far above what is already in the slot (m).
constexpr double kArmMargin = 0.02;       // Points this near the arm's capsules are the arm (m).

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

bool OnArm(const Eigen::Vector3d& p_W, const std::vector<Capsule>& arm) {
  return std::any_of(arm.begin(), arm.end(),
                     [&](const Capsule& c) { return DistanceToSegment(p_W, c.a, c.b) < c.radius + kArmMargin; });
}

// The slots of the layout on the diagonal along (1, sign) through the middle, middle included.
std::vector<int> DiagonalSlots(const CellLayout& layout, double sign) {
  std::vector<int> slots;
  for (size_t k = 0; k < layout.bin_slots.size(); ++k) {
    const Eigen::Vector3d& o = layout.bin_slots[k];
    if (std::abs(o.y() - sign * o.x()) < 1e-6) slots.push_back(static_cast<int>(k));
  }
  return slots;
}

}  // namespace

BinFill::BinFill(const CellLayout& layout) : layout_(layout) {
  if (layout.bin_slots.empty()) throw std::invalid_argument("BinFill: the cell layout has no bin slots");
  for (const auto& [category, p] : layout.p_W_bin) heights_[category].assign(layout.bin_slots.size(), 0.0);
}

void BinFill::See(const perception::Cloud& cloud, const Eigen::Isometry3d& X_WC, const std::vector<Capsule>& arm) {
  const double inside = layout_.bin_inner_half_width - kWallMargin;
  std::map<std::string, std::vector<std::vector<double>>> seen;  // Per bin, per slot: point heights.
  for (const auto& [category, p] : layout_.p_W_bin) seen[category].resize(layout_.bin_slots.size());
  for (const perception::PointT& point : cloud.points) {
    if (!std::isfinite(point.z)) continue;
    const Eigen::Vector3d p_W = X_WC * Eigen::Vector3d(point.x, point.y, point.z);
    for (const auto& [category, p_W_bin] : layout_.p_W_bin) {
      const Eigen::Vector3d d = p_W - p_W_bin;
      if (std::abs(d.x()) > inside || std::abs(d.y()) > inside || d.z() < kAboveFloor || d.z() > kTallest) continue;
      if (OnArm(p_W, arm)) break;
      for (size_t k = 0; k < layout_.bin_slots.size(); ++k) {
        const Eigen::Vector3d& o = layout_.bin_slots[k];
        if (std::abs(d.x() - o.x()) <= kSlotHalfWidth && std::abs(d.y() - o.y()) <= kSlotHalfWidth) {
          seen[category][k].push_back(d.z());
        }
      }
      break;  // Bins do not overlap.
    }
  }
  for (auto& [category, slots] : seen) {
    for (size_t k = 0; k < slots.size(); ++k) {
      std::vector<double>& z = slots[k];
      if (static_cast<int>(z.size()) < kTopRank) continue;
      std::nth_element(z.begin(), z.begin() + (kTopRank - 1), z.end(), std::greater<>());
      heights_[category][k] = std::max(heights_[category][k], z[kTopRank - 1]);
    }
  }
}

void BinFill::Released(const std::string& category, const BinRelease& release, double height) {
  std::vector<double>& slots = heights_.at(category);
  for (const int k : release.slots) slots[k] = std::max(slots[k], release.clearance + height);
}

const std::vector<double>& BinFill::Heights(const std::string& category) const {
  const auto bin = heights_.find(category);
  if (bin == heights_.end()) throw std::invalid_argument("cell layout: no bin for category '" + category + "'");
  return bin->second;
}

BinRelease BinFill::Upright(const std::string& category, int filled, double min_clearance) const {
  const std::vector<double>& slots = Heights(category);
  const int n = static_cast<int>(slots.size());
  // Heights within a centimetre count as the same: the layout's order decides between them.
  int best = filled % n;
  for (int i = 1; i < n; ++i) {
    const int k = (filled + i) % n;
    if (slots[k] < slots[best] - 0.01) best = k;
  }
  BinRelease release;
  release.p_W_floor = BinSlot(layout_, category, best);
  release.clearance = std::max(min_clearance, slots[best] + kAboveContents);
  release.yaw_step = layout_.place_yaw_step;
  release.slots = {best};
  return release;
}

BinRelease BinFill::Lying(const std::string& category) const {
  const std::vector<double>& slots = Heights(category);
  auto highest = [&](const std::vector<int>& diagonal) {
    double h = 0;
    for (const int k : diagonal) h = std::max(h, slots[k]);
    return h;
  };
  const std::vector<int> rising = DiagonalSlots(layout_, 1), falling = DiagonalSlots(layout_, -1);
  // The diagonals share the middle: the ends decide.
  auto ends = [&](const std::vector<int>& diagonal, const std::vector<int>& other) {
    std::vector<int> own;
    for (const int k : diagonal) {
      if (std::find(other.begin(), other.end(), k) == other.end()) own.push_back(k);
    }
    return own;
  };
  const bool along_rising = highest(ends(rising, falling)) <= highest(ends(falling, rising)) + 0.01;
  BinRelease release;
  release.p_W_floor = layout_.p_W_bin.at(category);
  release.slots = along_rising ? rising : falling;
  release.clearance = std::max(layout_.bin_wall_height + 0.01, highest(release.slots) + kAboveContents);
  // The object hangs along the TCP's x axis, (-sin yaw, cos yaw) for a top-down pinch at yaw.
  const double sign = along_rising ? 1.0 : -1.0;
  release.yaw_offset = std::atan2(-1.0, sign);
  release.yaw_step = M_PI;
  return release;
}

}  // namespace sortcell::cell
