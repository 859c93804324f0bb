#pragma once
/// @file
/// Scoring a sorting episode from the simulator's ground truth, after the fact: which object each
/// detection the policy acted on really was (the camera's label image), and where every object ended
/// up (a bin, the table, the floor). Nothing here feeds back into the policy's decisions.

#include <opencv2/core/mat.hpp>

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simcell/episode_metrics.h"
#include "cell/outcomes.h"
#include "cell/sorting_rules.h"
#include "sim/ground_truth.h"
#include "sim/model.h"

namespace sortcell::simcell {

/// An object placed on the table for the episode.
struct PlacedObject {
  std::string name, category;
  int body = -1;         ///< Body id in the model.
  int label = 0;         ///< Its value in the Kinect's label image.
  std::string bin;       ///< Where the cell's rules send it: sorted when it ends there.
  bool unknown = false;  ///< Not of the model's set (its bin is the reject bin).
};

/// What the policy saw of one detection, for the scorer.
struct DetectionRecord {
  const std::vector<int>* indices = nullptr;  ///< The segment's pixels.
  std::optional<std::string> predicted;       ///< Empty if the segment could not be described.
  double confidence = 0;
};

/// One grasp attempt as it ended.
struct AttemptRecord {
  /// The placed object its detection showed when the attempt started (ObjectOf), -1: none. Resolved
  /// then: the next view may be captured during the attempt's carry.
  int object = -1;
  std::string predicted;
  double confidence = 0;
  double start_s = 0, end_s = 0;  ///< Simulated time from leaving the observe pose to being back.
  bool grasped = false;           ///< Something held when the fingers closed.
  bool lifted = false;            ///< Still held after the lift.
  cell::AttemptResult result = cell::AttemptResult::kMotionFailed;
  double bound_s = 0;  ///< The least time the arm could have taken over the attempt's paths (cell::PhaseSpan::bound_s).
};

/// The table top's extent in x and y: an object outside it has fallen off (the table collides as an
/// unbounded plane, so an object pushed over the edge stays at z = 0).
struct TableExtent {
  Eigen::Vector2d min_xy, max_xy;
};

class EpisodeScorer {
 public:
  /// `label_count`: the largest value of the label image; `rules`: the cell's (an item the policy last
  /// recognised less surely than their reject_below was rejected).
  EpisodeScorer(std::vector<PlacedObject> objects, int label_count, const TableExtent& table,
                cell::SortingRules rules = {});

  /// After each observation, the policy's detections in its order.
  void Observe(const cv::Mat& labels, const std::vector<DetectionRecord>& detections);
  /// The policy gave detection `detection` of the last observation up as unreachable.
  void Unreachable(int detection);
  /// The policy gave detection `detection` of the last observation up as wider than the gripper.
  void Ungraspable(int detection);
  void Attempt(const AttemptRecord& attempt);

  /// Per placed object, its outcome from where it is now: in the bin the rules send it to (sorted), in
  /// another bin (wrong_bin), off the table or lifted and lost (dropped), given up without a plan or put back
  /// because its bin was out of reach (unreachable), given up as wider than the gripper (ungraspable),
  /// attempted but never lifted (grasp_failed), never seen (not_detected), else left_on_table.
  std::vector<ItemResult> Items(const sim::Data& data, const std::vector<sim::BinRef>& bins) const;

  /// How far the policy's grasp centre `xy` for a detection of the last observation is from the true
  /// centre of the object it shows (sim::ObjectExtentOf), and how far its width is off; empty if it shows none.
  std::optional<std::pair<double, double>> GraspErrors(int detection, const Eigen::Vector2d& xy, double width,
                                                       const sim::Model& model, const sim::Data& data) const;

  /// The object the last observation's detection showed (index into the placed objects, -1: none).
  int ObjectOf(int detection) const;
  const std::vector<PlacedObject>& objects() const { return objects_; }
  int attempts() const { return attempts_; }
  int grasps() const { return grasps_; }

 private:
  struct Track {
    bool seen = false, unreachable = false, ungraspable = false, lifted = false;
    int attempts = 0;
    double cycle_time_s = 0, cycle_bound_s = 0;
    std::optional<std::string> predicted;
    double confidence = 0;
  };
  cell::ItemOutcome OutcomeOf(size_t object, const sim::Data& data, const std::optional<sim::BinRef>& in_bin) const;
  std::optional<sim::BinRef> BinHolding(size_t object, const sim::Data& data,
                                        const std::vector<sim::BinRef>& bins) const;

  std::vector<PlacedObject> objects_;
  int label_count_;
  TableExtent table_;
  cell::SortingRules rules_;
  std::vector<Track> tracks_;
  std::vector<int> last_objects_;  // Per detection of the last observation.
  int attempts_ = 0, grasps_ = 0;
};

}  // namespace sortcell::simcell
