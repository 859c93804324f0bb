#include "robot/pick_selection.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/enum_names.h"
#include "robot/gripper_geometry.h"

namespace sortcell::robot {

constexpr EnumNames<SkipReason, 3> kSkipReasonNames{{{SkipReason::kNone, "none"},
                                                     {SkipReason::kUnreachable, "unreachable"},
                                                     {SkipReason::kGraspFailed, "grasp_failed"}}};

const char* ToString(SkipReason reason) { return NameOf(kSkipReasonNames, reason); }

PickMemory::PickMemory(const PickMemoryOptions& options)
    : radius_(options.same_object_radius), max_attempts_(options.max_attempts_per_position) {
  if (!(radius_ > 0) || max_attempts_ < 1) {
    throw std::invalid_argument("pick memory: expected same_object_radius > 0 and max_attempts_per_position >= 1");
  }
}

int PickMemory::Find(const Eigen::Vector2d& xy) const {
  int best = -1;
  double best_distance = radius_;
  for (size_t i = 0; i < entries_.size(); ++i) {
    const double d = (entries_[i].xy - xy).norm();
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

PickMemory::Entry& PickMemory::FindOrAdd(const Eigen::Vector2d& xy) {
  const int i = Find(xy);
  if (i < 0) {
    entries_.push_back({xy, 0, SkipReason::kNone});
    return entries_.back();
  }
  entries_[i].xy = xy;  // Follow the object as it is nudged.
  return entries_[i];
}

int PickMemory::RecordAttempt(const Eigen::Vector2d& xy) {
  Entry& e = FindOrAdd(xy);
  if (++e.attempts >= max_attempts_ && e.skipped == SkipReason::kNone) e.skipped = SkipReason::kGraspFailed;
  return e.attempts;
}

int PickMemory::Attempts(const Eigen::Vector2d& xy) const {
  const int i = Find(xy);
  return i < 0 ? 0 : entries_[i].attempts;
}

void PickMemory::Skip(const Eigen::Vector2d& xy, SkipReason reason) { FindOrAdd(xy).skipped = reason; }

SkipReason PickMemory::Skipped(const Eigen::Vector2d& xy) const {
  const int i = Find(xy);
  return i < 0 ? SkipReason::kNone : entries_[i].skipped;
}

namespace {

// The gripper body's outline widened by this (m) when looking for a neighbour's points under it, and
// the margin by which a neighbour must be lower than the finger tips to let them pass: the Kinect's noise.
constexpr double kBodyMargin = 0.005;

// Distance (m) from a point, in the grasp's frame (u along the closing direction, v across), to the
// finger on the +u side; the other finger is its mirror image.
double DistanceToFinger(double u, double v, double open_gap) {
  const double near = 0.5 * open_gap, far = near + kFingerDepth;
  const double du = std::fmax(0.0, std::fmax(near - std::abs(u), std::abs(u) - far));
  const double dv = std::fmax(0.0, std::abs(v) - kFingerHalfWidth);
  return std::hypot(du, dv);
}

}  // namespace

double FingerClearance(const Eigen::Vector2d& centre_xy, double yaw, double open_gap, const Neighbours& neighbours,
                       double tips_z) {
  const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw)), across(-along.y(), along.x());
  double clearance = INFINITY;
  const auto distance = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d r = p - centre_xy;
    return DistanceToFinger(r.dot(along), r.dot(across), open_gap);
  };
  // Below the finger tips (tops known): not in the fingers' way.
  const auto below = [&](const std::vector<double>& tops, size_t k, size_t count) {
    return tops.size() == count && tops[k] + kBodyMargin < tips_z;
  };
  for (size_t k = 0; k < neighbours.p_xy.size(); ++k) {
    if (below(neighbours.p_z, k, neighbours.p_xy.size())) continue;
    clearance = std::fmin(clearance, distance(neighbours.p_xy[k]));
  }
  for (size_t k = 0; k < neighbours.discs.size(); ++k) {
    if (below(neighbours.disc_top_z, k, neighbours.discs.size())) continue;
    const auto& [centre, radius] = neighbours.discs[k];
    clearance = std::fmin(clearance, distance(centre) - radius);
  }
  return clearance;
}

double LowestTcpAboveNeighbours(const Eigen::Vector2d& centre_xy, double yaw, const Neighbours& neighbours,
                                double margin, double clearance) {
  const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw)), across(-along.y(), along.x());
  if (neighbours.p_z.size() != neighbours.p_xy.size()) return -INFINITY;
  double lowest = -INFINITY;
  for (size_t k = 0; k < neighbours.p_xy.size(); ++k) {
    const Eigen::Vector2d r = neighbours.p_xy[k] - centre_xy;
    const double to_palm = std::hypot(std::fmax(0.0, std::abs(r.dot(along)) - kPalmHalfLength),
                                      std::fmax(0.0, std::abs(r.dot(across)) - kPalmHalfWidth));
    const double z = neighbours.p_z[k] + clearance;
    if (to_palm <= margin) lowest = std::fmax(lowest, z - kPalmBeforeTcp);
    if (r.norm() - kHousingRadius <= margin) lowest = std::fmax(lowest, z - kHousingBeforeTcp);
  }
  return lowest;
}

std::vector<ObjectFootprint> RoundWays(const ObjectFootprint& object, int directions) {
  std::vector<ObjectFootprint> ways(directions, object);
  for (int k = 1; k < directions; ++k) ways[k].pinch_yaw = object.pinch_yaw + k * M_PI / directions;
  return ways;
}

ClearGrasp ClearestGrasp(const std::vector<ObjectFootprint>& ways, double side_clearance, const Neighbours& neighbours,
                         double enough) {
  return ClearestGrasp(ways, std::vector<double>(ways.size(), side_clearance), neighbours, enough);
}

ClearGrasp ClearestGrasp(const std::vector<ObjectFootprint>& ways, const std::vector<double>& side_clearances,
                         const Neighbours& neighbours, double enough) {
  if (ways.empty()) throw std::invalid_argument("clearest grasp: no way to pinch the object given");
  if (side_clearances.size() != ways.size()) {
    throw std::invalid_argument("clearest grasp: " + std::to_string(side_clearances.size()) + " clearances for " +
                                std::to_string(ways.size()) + " ways");
  }
  ClearGrasp best{ways.front(), -INFINITY};
  for (size_t k = 0; k < ways.size(); ++k) {
    const ObjectFootprint& way = ways[k];
    GraspOptions options;
    options.min_tcp_z =
        LowestTcpAboveNeighbours(way.centre_xy, way.pinch_yaw, neighbours, kBodyMargin, options.palm_clearance);
    const double tips_z = way.base_z + GraspHeight(way, options) - kFingerTipBeyondTcp;
    const double clearance =
        FingerClearance(way.centre_xy, way.pinch_yaw, way.width + 2 * side_clearances[k], neighbours, tips_z);
    if (k == 0 && clearance >= enough) return {way, clearance, options.min_tcp_z};
    if (clearance > best.clearance + 1e-4) best = {way, clearance, options.min_tcp_z};
  }
  return best;
}

int ChooseNextPick(const std::vector<ObjectFootprint>& candidates, const PickMemory& memory) {
  int best = -1;
  double best_room = -INFINITY;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (memory.Skipped(candidates[i].centre_xy) != SkipReason::kNone) continue;
    double room = INFINITY;
    for (size_t j = 0; j < candidates.size(); ++j) {
      if (j == i) continue;
      room = std::min(room, (candidates[i].centre_xy - candidates[j].centre_xy).norm() -
                                0.5 * (candidates[i].width + candidates[j].width));
    }
    if (room > best_room) {
      best_room = room;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace sortcell::robot
