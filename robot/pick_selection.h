#pragma once
/// @file
/// Which object the sorting loop picks next, and what it remembers between captures. Objects move
/// (a missed grasp nudges them, a neighbour's pick disturbs them) and the camera gives no identities,
/// so the loop remembers table positions: "the cluster near here" is the object it tried before.

#include <Eigen/Core>

#include <utility>
#include <vector>

#include "robot/grasp_planner.h"

namespace sortcell::robot {

enum class SkipReason { kNone, kUnreachable, kGraspFailed };
const char* ToString(SkipReason reason);

class PickMemory {
 public:
  /// @param radius        Clusters whose centres are this close are the same object (m).
  /// @param max_attempts  Grasp attempts at one position before it is given up.
  explicit PickMemory(double radius = 0.04, int max_attempts = 3);

  /// Counts a grasp attempt at xy; when the count reaches max_attempts, the position is given up
  /// (kGraspFailed). Returns the count.
  int RecordAttempt(const Eigen::Vector2d& xy);
  /// Attempts recorded near xy.
  int Attempts(const Eigen::Vector2d& xy) const;
  /// Gives up the position xy for `reason`.
  void Skip(const Eigen::Vector2d& xy, SkipReason reason);
  /// Why the position xy was given up, or kNone.
  SkipReason Skipped(const Eigen::Vector2d& xy) const;
  int max_attempts() const { return max_attempts_; }

 private:
  struct Entry {
    Eigen::Vector2d xy;
    int attempts = 0;
    SkipReason skipped = SkipReason::kNone;
  };
  int Find(const Eigen::Vector2d& xy) const;  // Index of the nearest entry within radius_, or -1.
  Entry& FindOrAdd(const Eigen::Vector2d& xy);

  double radius_;
  int max_attempts_;
  std::vector<Entry> entries_;
};

/// What stands around the object to pick, seen from above: the other objects' points, and their
/// footprints as discs (centre, half their width) for the backs the camera does not see.
struct Neighbours {
  std::vector<Eigen::Vector2d> p_xy;
  std::vector<std::pair<Eigen::Vector2d, double>> discs;
};

/// How far the open fingers of a top-down grasp at centre_xy, closing along `yaw` and opened to
/// `open_gap`, stay from the neighbours (m): 0 where a neighbour's point is in a finger's way, negative
/// where a finger reaches into a neighbour's footprint disc.
double FingerClearance(const Eigen::Vector2d& centre_xy, double yaw, double open_gap, const Neighbours& neighbours);

/// For a round object (the fingers may close on it from any side), the direction to close along:
/// its own pinch_yaw while the open fingers clear the neighbours by `enough` there, else the one of
/// twelve (15 degree steps) with the most clearance. A neighbour standing where a finger comes down
/// is knocked over or keeps the finger from closing.
double ClearestPinchYaw(const ObjectFootprint& object, double open_gap, const Neighbours& neighbours,
                        double enough = 0.015);

/// The candidate to pick next: of those not given up, the one with the most free room around it
/// (distance from its centre to the nearest other object's centre, less both half-widths), so the
/// open fingers are least likely to touch a neighbour and every pick makes room for the next.
/// Returns its index, or -1 if every candidate was given up.
int ChooseNextPick(const std::vector<ObjectFootprint>& candidates, const PickMemory& memory);

}  // namespace sortcell::robot
