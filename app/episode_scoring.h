#pragma once
/// @file
/// Scoring a sorting episode from the simulator's ground truth, after the fact: which object each
/// detection the loop acted on really was (the camera's label image), and where every object ended
/// up (a bin, the table, the floor). Nothing here feeds back into the loop's decisions.

#include <opencv2/core/mat.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/model.h"

namespace sortcell::app {

/// An object placed on the table for the episode.
struct PlacedObject {
  std::string name, category;
  int body = -1;   ///< Body id in the model.
  int label = 0;   ///< Its value in the Kinect's label image.
};

/// What the loop saw of one detection, for the scorer.
struct DetectionRecord {
  const std::vector<int>* indices = nullptr;  ///< The segment's pixels.
  std::optional<std::string> predicted;       ///< Empty if the segment could not be described.
  double confidence = 0;
};

/// One grasp attempt as it ended.
struct AttemptRecord {
  int detection = -1;  ///< Index into the last observation's detections.
  std::string predicted;
  double confidence = 0;
  double start_s = 0, end_s = 0;  ///< Simulated time from leaving the observe pose to being back.
  bool grasped = false;   ///< Something held when the fingers closed.
  bool lifted = false;    ///< Still held after the lift.
};

/// The episode's outcomes, in the order of metrics.json's counts.
inline const std::vector<std::string> kOutcomes{"sorted", "wrong_bin", "dropped", "grasp_failed", "unreachable",
                                                 "not_detected", "left_on_table"};

class EpisodeScorer {
 public:
  /// `label_count`: the largest value of the label image.
  EpisodeScorer(std::vector<PlacedObject> objects, int label_count);

  /// After each observation, the loop's detections in its order.
  void Observe(const cv::Mat& labels, const std::vector<DetectionRecord>& detections);
  /// The loop gave detection `detection` of the last observation up as unreachable.
  void Unreachable(int detection);
  void Attempt(const AttemptRecord& attempt);

  /// Per placed object: {"name", "true_category", "predicted_category" (null if never classified),
  /// "confidence", "attempts", "outcome", "cycle_time_s" (null if never attempted), "final_xyz"}.
  /// `bins`: body id of each category's bin ("bin_<category>").
  nlohmann::json Items(const sim::Data& data, const std::vector<std::pair<std::string, int>>& bins) const;

  /// How far the loop's grasp centre `xy` for a detection of the last observation is from the true
  /// centre of the object it shows (sim::ObjectExtentOf), and how far its width is off; NaN if it shows none.
  std::pair<double, double> GraspErrors(int detection, const Eigen::Vector2d& xy, double width, const sim::Model& model,
                                        const sim::Data& data) const;

  /// The object the last observation's detection showed (index into the placed objects, -1: none).
  int ObjectOf(int detection) const;
  int attempts() const { return attempts_; }
  int grasps() const { return grasps_; }

 private:
  struct Track {
    bool seen = false, unreachable = false, lifted = false;
    int attempts = 0;
    double cycle_time_s = 0;
    std::optional<std::string> predicted;
    double confidence = 0;
  };
  std::vector<PlacedObject> objects_;
  int label_count_;
  std::vector<Track> tracks_;
  std::vector<int> last_objects_;  // Per detection of the last observation.
  int attempts_ = 0, grasps_ = 0;
};

/// Counts over the items of metrics.json: one episode's, or many episodes' pooled (sweeps).
struct ItemTally {
  int items = 0, classified = 0, recognised = 0;
  int completed = 0;  ///< Items that reached a bin (sorted or wrong_bin).
  double cycle_s = 0;  ///< Their cycle times, summed.
  std::map<std::string, int> outcomes;

  void Add(const nlohmann::json& item);
  int Count(const std::string& outcome) const;
  /// {outcome: count} with every outcome of kOutcomes.
  nlohmann::json OutcomeCounts() const;
};

/// The episode summary: item and outcome counts, correct-sort rate, recognition accuracy (of the
/// items classified), grasps that held and the grasp success rate, mean cycle time of the items that
/// reached a bin, plus the given run figures.
nlohmann::json SummarizeEpisode(const nlohmann::json& items, int attempts, int grasps, const nlohmann::json& run);

}  // namespace sortcell::app
