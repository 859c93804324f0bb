#pragma once
/// @file
/// The episode harness's side of the policy: it scores what the policy reports (the scorer reads the
/// truth of each capture through the simulated cell's own channel), keeps the attempts log and draws
/// the review video's overlay and inset. Nothing here is consulted by a decision.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simcell/episode_metrics.h"
#include "simcell/episode_scoring.h"
#include "simcell/sim_cell.h"
#include "cell/sorting_policy.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {

class EpisodeRecorder : public cell::PolicyObserver {
 public:
  /// `video` may be null. `max_attempts_per_object` is for the overlay. `stills`: a folder for the still
  /// of every decision (EpisodeOptions::stills), or empty.
  EpisodeRecorder(EpisodeScorer& scorer, const SimCell& cell, const sim::Model& model, const sim::Data& data,
                  sim::VideoRecorder* video, uint64_t seed, int max_attempts_per_object,
                  std::filesystem::path stills = {});

  void Observing() override;
  void Observed(const perception::Cloud& cloud, const cell::Observation& observation,
                double perception_wall_s) override;
  void Skipped(int detection, const cell::Detection& seen, robot::GraspStatus why) override;
  void AttemptStarting(const cell::AttemptReport& report) override;
  void AttemptEnded(const cell::AttemptReport& report) override;
  void Grasped() override;
  void Lowered() override;

  /// Slip of held objects in the gripper from the grasp closing to the bin (truth).
  struct Slip {
    double max_mm = 0, sum_mm = 0;
    double max_deg = 0;  ///< Largest turn in the gripper.
    int carries = 0;
  };
  const Slip& slip() const { return slip_; }

  /// The video overlay's middle line (the current activity); no-op without a video.
  void ShowStatus(const std::string& current);
  const std::vector<AttemptLogEntry>& attempts_log() const { return log_; }
  double perception_wall_s() const { return perception_wall_s_; }
  /// Mean simulated seconds per attempt in each motion phase.
  std::map<std::string, double> CyclePhases() const;
  /// The same for the least time the arm could have taken over each phase's paths.
  std::map<std::string, double> CyclePhaseBounds() const;

 private:
  void ShowObservation(const perception::Cloud& cloud, const std::vector<cell::Detection>& detections);
  std::filesystem::path stills_;

  EpisodeScorer& scorer_;
  const SimCell& cell_;
  const sim::Model& model_;
  const sim::Data& data_;
  sim::VideoRecorder* video_;
  uint64_t seed_;
  int max_attempts_per_object_;
  std::vector<AttemptLogEntry> log_;
  std::optional<std::pair<double, double>> truth_errors_;  // Of the attempt in progress.
  int attempted_object_ = -1;  // The placed object the attempt in progress went for (-1: none).
  int tcp_site_;
  std::optional<Eigen::Isometry3d> X_TO_grasped_;  // How the held object sat in the gripper at the grasp.
  Slip slip_;
  double perception_wall_s_ = 0;
  std::map<std::string, double> phase_s_;        // Simulated seconds in each phase, over every attempt.
  std::map<std::string, double> phase_bound_s_;  // The arm's least time for each phase, over every attempt.
  int attempts_ = 0;
  int released_ = 0, missed_ = 0, dropped_ = 0, skipped_ = 0;
};

}  // namespace sortcell::simcell
