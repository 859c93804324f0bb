#pragma once
/// @file
/// The sorting cell's policy (paper section 2.3), over any CellIo: capture, describe and classify
/// every cluster, choose the one with the most room around it, plan a top-down grasp from its
/// footprint, pick it and put it into its category's bin, and again, until nothing pickable is left
/// in view or a budget runs out. The arm does not go home between items: the next view is captured
/// during the carry, as soon as the arm and the held object are out of the camera's view of the
/// workspace (WorkspaceView, from the arm's kinematics and the calibrated camera), and the next pick is
/// planned from it while the carry goes on, and starts from the bin. Nothing in view changes after
/// that capture unless the object is lost on the way; then (and after a miss) the arm goes home and
/// captures again. A missed grasp is retried from a fresh capture, at most
/// pick.max_attempts_per_position times at one table position; which cluster and how: cell/pick_choice.h. It decides
/// from the camera's clouds, the encoders and the gripper's sensors only.

#include <map>
#include <optional>
#include <string>

#include "cell/arm_view.h"
#include "cell/bin_fill.h"
#include "cell/cell_io.h"
#include "cell/cell_layout.h"
#include "cell/motion_sequencer.h"
#include "cell/outcomes.h"
#include "cell/pick_choice.h"
#include "cell/pick_and_place.h"
#include "cell/scene_observation.h"
#include "perception/recognition_model.h"
#include "robot/grasp_planner.h"
#include "robot/pick_selection.h"

namespace sortcell::cell {

struct PolicyOptions {
  robot::PickMemoryOptions pick;  ///< One object across captures, and the attempts at it.
  int max_attempts = 24;          ///< Grasp attempts in all before the episode ends.
  double time_limit_s = 330;      ///< Seconds on the cell's clock from the start before it ends.
};

/// One attempt, as the policy saw it go.
struct AttemptReport {
  int detection = -1;               ///< Index into the last observation's detections.
  const Detection* seen = nullptr;  ///< That detection (valid during the callback).
  int attempt = 0;                  ///< 1 for the first attempt at this position.
  double start_s = 0, end_s = 0;    ///< The cell's clock from leaving where the arm was (home or the last
                                    ///< bin) to the release into the bin (or back home after a miss).
  BinRelease release;               ///< Where in its bin it was to be let go.
  PickReport pick;
  std::vector<PhaseSpan> phases;  ///< The attempt's motion phases, in order (filled when it ended).
};

/// What the policy reports as it goes (the episode harness: scoring, logs, video). Never consulted
/// for a decision.
class PolicyObserver {
 public:
  virtual ~PolicyObserver() = default;
  /// About to capture.
  virtual void Observing() {}
  /// A capture and what the policy made of it; `perception_wall_s`: wall time of perception.
  virtual void Observed(const perception::Cloud& /*cloud*/, const Observation& /*observation*/,
                        double /*perception_wall_s*/) {}
  /// Detection `detection` of the last observation has no grasp plan and is given up.
  virtual void Skipped(int /*detection*/, const Detection& /*seen*/, robot::GraspStatus /*why*/) {}
  /// About to attempt detection `report.detection` (report.pick not yet filled).
  virtual void AttemptStarting(const AttemptReport& /*report*/) {}
  /// The fingers closed on the object and hold it / it was lowered into the bin, before the release.
  virtual void Grasped() {}
  virtual void Lowered() {}
  virtual void AttemptEnded(const AttemptReport& /*report*/) {}
};

struct PolicyResult {
  EpisodeStatus status = EpisodeStatus::kCompleted;
  int attempts = 0;  ///< Grasp attempts made.
  int frames = 0;    ///< Captures taken.
};

class SortingPolicy {
 public:
  /// Objects go where the layout's rules send them (CellLayout::rules).
  /// @throws std::invalid_argument if the rules send a class of `model` to no bin or to a bin the
  ///         layout lacks, or an option is out of range (attempt limits < 1, time limit <= 0).
  SortingPolicy(CellIo& io, const CellLayout& layout, const CameraCalibration& calibration,
                const perception::RecognitionModel& model, const PolicyOptions& options,
                PolicyObserver* observer = nullptr);
  SortingPolicy(const SortingPolicy&) = delete;  // It refers to its own members (observer_).
  SortingPolicy& operator=(const SortingPolicy&) = delete;

  /// Sorts until nothing pickable is left in view or a budget runs out. Starts from the observe pose.
  PolicyResult Run();

  const MotionSequencer& motions() const { return motions_; }

 private:
  // Captures and observes; `held`: what the arm holds if it is carrying something.
  Observation Observe(const std::optional<HeldObject>& held = std::nullopt);
  AttemptReport Attempt(const std::vector<Detection>& detections, int index, int attempt, const robot::GraspPlan& plan,
                        const std::optional<BinExit>& exit, std::optional<Observation>& next_view);

  CellIo& io_;
  const CellLayout& layout_;
  const CameraCalibration& calibration_;
  const perception::RecognitionModel& model_;
  PolicyOptions options_;
  PolicyObserver no_observer_;
  PolicyObserver& observer_;
  MotionSequencer motions_;
  perception::SegmentationParams segmentation_;
  WorkspaceView view_;                        // Whether the arm hides the workspace from the camera.
  std::map<std::string, int> released_into_;  // Objects released into each bin so far.
  // Captures only to see into the bins (no perception of the table).
  void LookIntoBins(const HeldObject& held);
  // Where in its bin to let go of `seen`, held grasp_height above its bottom, from what is there and
  // where the arm can let it go.
  BinRelease ChooseRelease(const Detection& seen, int filled, double min_clearance, double grasp_height) const;

  BinFill bins_;                               // What is in the bins already.
  std::optional<std::string> unseen_release_;  // The bin of the last release, until a capture saw it.
  FixedObstacles bin_walls_;                   // What open fingers must keep clear of besides objects.
};

}  // namespace sortcell::cell
