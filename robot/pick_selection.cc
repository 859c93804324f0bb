#include "robot/pick_selection.h"

#include <cmath>
#include <stdexcept>

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
