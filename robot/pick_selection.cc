#include "robot/pick_selection.h"

#include <cmath>
#include <stdexcept>

#include "robot/gripper_geometry.h"

namespace sortcell::robot {

const char* ToString(SkipReason reason) {
  switch (reason) {
    case SkipReason::kNone: return "none";
    case SkipReason::kUnreachable: return "unreachable";
    case SkipReason::kGraspFailed: return "grasp_failed";
  }
  return "?";
}

PickMemory::PickMemory(double radius, int max_attempts) : radius_(radius), max_attempts_(max_attempts) {
  if (!(radius > 0) || max_attempts < 1) {
    throw std::invalid_argument("pick memory: expected radius > 0 and max_attempts >= 1");
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

// Distance (m) from a point, in the grasp's frame (u along the closing direction, v across), to the
// finger on the +u side; the other finger is its mirror image.
double DistanceToFinger(double u, double v, double open_gap) {
  const double near = 0.5 * open_gap, far = near + kFingerDepth;
  const double du = std::fmax(0.0, std::fmax(near - std::abs(u), std::abs(u) - far));
  const double dv = std::fmax(0.0, std::abs(v) - kFingerHalfWidth);
  return std::hypot(du, dv);
}

}  // namespace

double FingerClearance(const Eigen::Vector2d& centre_xy, double yaw, double open_gap, const Neighbours& neighbours) {
  const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw)), across(-along.y(), along.x());
  double clearance = INFINITY;
  const auto distance = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d r = p - centre_xy;
    return DistanceToFinger(r.dot(along), r.dot(across), open_gap);
  };
  for (const Eigen::Vector2d& p : neighbours.p_xy) clearance = std::fmin(clearance, distance(p));
  for (const auto& [centre, radius] : neighbours.discs) clearance = std::fmin(clearance, distance(centre) - radius);
  return clearance;
}

double ClearestPinchYaw(const ObjectFootprint& object, double open_gap, const Neighbours& neighbours, double enough) {
  constexpr int kDirections = 12;  // Over half a turn: the other half is the same pair of fingers.
  double best_yaw = object.pinch_yaw;
  double best = FingerClearance(object.centre_xy, best_yaw, open_gap, neighbours);
  if (best >= enough) return best_yaw;
  for (int k = 1; k < kDirections; ++k) {
    const double yaw = object.pinch_yaw + k * M_PI / kDirections;
    const double clearance = FingerClearance(object.centre_xy, yaw, open_gap, neighbours);
    if (clearance > best + 1e-4) {
      best = clearance;
      best_yaw = yaw;
    }
  }
  return best_yaw;
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
