#pragma once
/// @file
/// Which object the sorting loop picks next, and what it remembers between captures. Objects move
/// (a missed grasp nudges them, a neighbour's pick disturbs them) and the camera gives no identities,
/// so the loop remembers table positions: "the cluster near here" is the object it tried before.

#include <Eigen/Core>

#include <cmath>

#include <utility>
#include <vector>

#include "robot/grasp_planner.h"

namespace sortcell::robot {

enum class SkipReason { kNone, kUnreachable, kGraspFailed };
const char* ToString(SkipReason reason);

/// What the loop remembers between captures, and for how long it keeps trying one object.
struct PickMemoryOptions {
  double same_object_radius = 0.04;   ///< Clusters whose centres are this close are the same object (m).
  int max_attempts_per_position = 3;  ///< Grasp attempts at one table position before it is given up.
};

class PickMemory {
 public:
  /// @throws std::invalid_argument unless same_object_radius > 0 and max_attempts_per_position >= 1.
  explicit PickMemory(const PickMemoryOptions& options = {});

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
/// footprints as discs (centre, half their width) for the backs the camera does not see; with how high
/// each point is and each disc's object reaches (world z, m), in the same order (empty: not known).
struct Neighbours {
  std::vector<Eigen::Vector2d> p_xy;
  std::vector<std::pair<Eigen::Vector2d, double>> discs;
  std::vector<double> p_z;
  std::vector<double> disc_top_z;
};

/// How far the open fingers of a top-down grasp at centre_xy, closing along `yaw` and opened to
/// `open_gap`, stay from the neighbours (m): 0 where a neighbour's point is in a finger's way, negative
/// where a finger reaches into a neighbour's footprint disc. Where the neighbours' tops are known, those
/// lower than the finger tips come down to (`tips_z`, world z, m; by a margin) are not in the way.
double FingerClearance(const Eigen::Vector2d& centre_xy, double yaw, double open_gap, const Neighbours& neighbours,
                       double tips_z = -INFINITY);

/// The lowest TCP height (world z, m) at which the gripper's body above the fingers (the palm, the
/// housing), seen from above as outlines widened by `margin` (m), stays `clearance` (m) above every
/// neighbour point under it, for a top-down grasp at centre_xy closing along `yaw`; -infinity where no
/// point is under it or their heights are unknown. The points only, at their own heights: a neighbour's
/// top is what the camera above sees best, and a bottle's neck leaves room its footprint disc does not.
double LowestTcpAboveNeighbours(const Eigen::Vector2d& centre_xy, double yaw, const Neighbours& neighbours,
                                double margin, double clearance);

/// A round object (the fingers may close on it from any side) pinched from `directions` directions
/// over half a turn (the other half is the same pair of fingers), its own pinch_yaw first.
std::vector<ObjectFootprint> RoundWays(const ObjectFootprint& object, int directions = 12);

/// One way to grasp an object, how far its open fingers stay from the neighbours (m), and the lowest
/// TCP height the neighbours leave the gripper's body there (world z, m; LowestTcpAboveNeighbours).
struct ClearGrasp {
  ObjectFootprint footprint;
  double clearance = 0;
  double min_tcp_z = -INFINITY;
};

/// Of the ways to pinch one object (`ways`: the same object, other pinch directions; the first is the
/// preferred one), the preferred one while its open fingers (its width plus `side_clearance` per side)
/// clear the neighbours by `enough` (those lower than where the finger tips come down do not count),
/// else the one that clears them most; with the lowest TCP height each leaves the gripper's body, to
/// which the grasp rises as far as the object allows (GraspHeight). A neighbour under the body that
/// the grasp cannot rise above does not block the pick: waiting for such picks sent the cell to the
/// partly hidden objects first, whose footprints are the least sure (clutter_100 97.8 % against 98.8 %).
/// @throws std::invalid_argument if `ways` is empty.
ClearGrasp ClearestGrasp(const std::vector<ObjectFootprint>& ways, double side_clearance, const Neighbours& neighbours,
                         double enough = 0.015);
/// The same with each way's own clearance per side (`side_clearances`, one per way: a wider way opens
/// less beyond the object within the stroke).
/// @throws std::invalid_argument if `ways` is empty or the counts differ.
ClearGrasp ClearestGrasp(const std::vector<ObjectFootprint>& ways, const std::vector<double>& side_clearances,
                         const Neighbours& neighbours, double enough = 0.015);

/// The candidate to pick next: of those not given up, the one with the most free room around it
/// (distance from its centre to the nearest other object's centre, less both half-widths), so the
/// open fingers are least likely to touch a neighbour and every pick makes room for the next.
/// Returns its index, or -1 if every candidate was given up.
int ChooseNextPick(const std::vector<ObjectFootprint>& candidates, const PickMemory& memory);

}  // namespace sortcell::robot
