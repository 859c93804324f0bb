#pragma once
/// @file
/// The episode's metrics.json as structs: written from them, and read back into them (the sweep's
/// records carry an episode's items and summary). Reading is strict: a missing or mistyped key is an
/// error naming the key.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cell/outcomes.h"
#include "files/record_fields.h"

namespace sortcell::simcell {

/// One placed object at the end of the episode.
struct ItemResult {
  std::string name, true_category;
  std::optional<std::string> predicted_category;  ///< Null if never classified.
  double confidence = 0;
  int attempts = 0;
  cell::ItemOutcome outcome = cell::ItemOutcome::kLeftOnTable;
  std::optional<double> cycle_time_s;  ///< Null if never attempted.
  /// The least time the arm could have taken over the same paths, as fast as its joint speeds and
  /// torque budget allow, the fingers' phases as they ran (cell::PhaseSpan::bound_s); null if never
  /// attempted (or in records from before it).
  std::optional<double> cycle_bound_s;
  std::array<double, 3> final_xyz{};
  /// The bin the cell's rules send it to (an unknown object: the reject bin), and the bin it ended
  /// in (empty: none). Records from before the cell files have neither (both empty).
  std::string rule_bin, bin;
  /// From the sweep's unknown set: an object the model was not trained on.
  bool unknown = false;
  /// The policy's last look at it was less sure than the cell's reject_below: sent to the reject bin.
  bool rejected = false;
};

/// Counts per outcome, every outcome present.
using OutcomeCounts = std::map<cell::ItemOutcome, int>;

/// Figures of the run itself (not of the items).
struct RunFigures {
  cell::EpisodeStatus status = cell::EpisodeStatus::kCompleted;
  double sim_time_s = 0, wall_time_s = 0, real_time_factor = 0;
  int frames = 0;
  double perception_ms_per_frame = 0, render_ms_per_frame = 0;
  int video_frames = 0;
  double video_render_wall_s = 0;
  int mujoco_warnings = 0;
  /// The pick cycle by phase: mean simulated seconds per attempt in each motion phase (approach,
  /// descend, reach, grasp, lift, carry, lower, release, retreat, home, ...).
  std::map<std::string, double> cycle_phases_s;
  /// The same for the least time the arm could have taken over each phase's paths.
  std::map<std::string, double> cycle_phases_bound_s;
  /// Where the wall time went (s): "physics" (steps), "kinect_render", "kinect_noise", "label_render",
  /// "cloud" (the organized cloud), "perception", "video" (review frames), "other" (the rest).
  std::map<std::string, double> profile_wall_s;
  /// Inside the physics steps, from MuJoCo's stage timers (s): "collision_s", "constraint_s" (rows,
  /// solver and noslip), "smooth_s" (the rest), "step_s" (all, settling included), and the load they work
  /// on: "steps", "contacts_per_step", "constraint_rows_per_step" (means over the controlled steps).
  std::map<std::string, double> physics_profile;
  double tracking_max_error_rad = 0;  ///< Largest joint tracking error of the arm's controller.
  int torque_saturated_samples = 0;   ///< Control periods with a joint torque at its limit.
  /// How far held objects moved in the gripper from the grasp closing to the bin, before the release
  /// (truth, mm): the largest and the sum over the carries measured, and their number.
  double carry_slip_max_mm = 0, carry_slip_sum_mm = 0;
  double carry_turn_max_deg = 0;  ///< The largest turn of a held object in the gripper, same span (truth).
  int carries = 0;
};

/// RunFigures' keys in metrics.json's summary, with how a sweep pools them over episodes (per-attempt
/// means weighted by each episode's grasp attempts) and which are the machine's.
struct RunFiguresFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    using namespace files;  // NOLINT(google-build-using-namespace): the flags' names, in this list only.
    field("status", v.status);
    field("sim_time_s", v.sim_time_s, kSum);
    field("wall_time_s", v.wall_time_s, kSum | kMachine);
    field("real_time_factor", v.real_time_factor, kDerived | kMachine);
    field("frames", v.frames, kSum);
    field("perception_ms_per_frame", v.perception_ms_per_frame, kMachine);
    field("render_ms_per_frame", v.render_ms_per_frame, kMachine);
    field("video_frames", v.video_frames, kSum | kMachine);
    field("video_render_wall_s", v.video_render_wall_s, kSum | kMachine);
    field("mujoco_warnings", v.mujoco_warnings, kSum);
    field("cycle_phases_s", v.cycle_phases_s, kAdded | kWeightedMean);
    field("cycle_phases_bound_s", v.cycle_phases_bound_s, kAdded | kWeightedMean);
    field("profile_wall_s", v.profile_wall_s, kAdded | kSum | kMachine);
    field("physics_profile", v.physics_profile, kAdded);
    field("tracking_max_error_rad", v.tracking_max_error_rad, kAdded | kMax);
    field("torque_saturated_samples", v.torque_saturated_samples, kAdded | kSum);
    field("carry_slip_max_mm", v.carry_slip_max_mm, kAdded | kMax);
    field("carry_turn_max_deg", v.carry_turn_max_deg, kAdded | kMax);
    field("carries", v.carries, kAdded | kSum);
  }
};
RunFiguresFields RecordFieldsOf(const RunFigures*);

/// Adds one episode's run figures to `pooled` as their flags say; `attempts` (its grasp attempts)
/// weighs its per-attempt means. The slips' sum, not a key of its own, is summed too.
void PoolRunFigures(RunFigures& pooled, const RunFigures& run, int attempts);
/// Ends a pool of `attempts` attempts in all: per-attempt sums become means, and the real-time factor
/// is the pooled simulated time over the pooled wall time.
void FinishRunPool(RunFigures& pooled, int attempts);

/// The hand-eye self-calibration an episode started with (simcell/calibration_run.h).
struct CalibrationFigures {
  std::string status;  ///< cell::ToString(cell::HandEyeStatus).
  int sightings = 0, inliers = 0;
  double rms_residual_m = 0;  ///< Of the fit, over its inliers.
  double duration_s = 0;      ///< Simulated.
  /// Scoring: the calibrated and the prior (nominal) camera pose against the true one.
  double error_m = 0, error_rad = 0, prior_error_m = 0, prior_error_rad = 0;
};

struct EpisodeSummary {
  int items = 0;
  OutcomeCounts outcomes;
  std::optional<double> correct_sort_rate, recognition_accuracy;  ///< Null without items / classified items.
  int items_classified = 0;
  int grasp_attempts = 0, grasps = 0;
  std::optional<double> grasp_success_rate, mean_cycle_time_s;
  /// The mean least time of the same items' cycles (ItemResult::cycle_bound_s), and the cycles' total
  /// over the bounds' total: how many times slower than the arm could go the cell sorts.
  std::optional<double> mean_cycle_bound_s, cycle_to_bound;
  std::optional<double> picks_per_hour;  ///< Items sorted per simulated hour (null without simulated time).
  RunFigures run;
  std::optional<CalibrationFigures> calibration;  ///< Null when the episode did not self-calibrate.
};

/// The scene variations the episode ran with.
struct EpisodeVariation {
  double light_intensity = 1, noise_scale = 1, friction_scale = 1, mass_scale = 1;
  double camera_shift_m = 0, camera_turn_rad = 0;
  double colour_jitter = 0;
};

/// A phase of an attempt and the hold the gripper's sensors judged at its end (robot::ToString(HoldState)).
struct PhaseHold {
  std::string phase;
  double end_s = 0;
  std::string hold;
  double gap_m = 0;
};

/// One line of the attempts log: a grasp attempt, or a cluster skipped without one.
struct AttemptLogEntry {
  double time_s = 0;
  std::optional<double> duration_s;  ///< Null for a skipped cluster.
  std::string category;
  std::string bin;  ///< Where the cell's rules send it (empty: undescribed).
  std::optional<double> confidence;
  std::array<double, 2> xy{};
  std::optional<double> pinch_yaw, width_m, top_z_m;
  std::optional<bool> lying;                  ///< Seen lying on its side.
  std::optional<double> release_clearance_m;  ///< Its bottom above the bin floor when let go (planned).
  std::string result;                         ///< An attempt result (cell::ToString) or "skipped: <grasp status>".
  std::optional<std::string> truth_object;    ///< Scoring: the object the cluster really was.
  std::optional<double> truth_centre_error_m, truth_width_error_m;
  std::string detail;
  std::vector<PhaseHold> phases;                  ///< An attempt's phases in order; empty for a skipped cluster.
  std::optional<double> max_friction_use;         ///< The most of the pads' friction the hold used.
  std::optional<double> recentred_m;              ///< Grasped again this far over (off-centre), or null.
  std::optional<std::string> squeezed_harder_in;  ///< The phase the grip was firmed in (near slipping).
};

struct EpisodeMetrics {
  uint64_t seed = 0;
  std::string scene, cell, object_set, model, descriptor;
  EpisodeVariation variation;
  std::vector<ItemResult> items;
  EpisodeSummary summary;
  std::vector<AttemptLogEntry> attempts;
  std::optional<std::string> video;
};

/// Counts over items: one episode's, or many episodes' pooled (sweeps).
struct ItemTally {
  int items = 0, classified = 0, recognised = 0;
  /// Objects of the unknown set: in all, in the reject bin, in another bin; objects of the model's set
  /// in all and rejected (recognised less surely than reject_below).
  int unknown = 0, unknown_rejected = 0, unknown_in_category_bin = 0, known = 0, known_rejected = 0;
  int completed = 0;   ///< Items that reached a bin (sorted or wrong_bin) with a cycle time.
  double cycle_s = 0;  ///< Their cycle times, summed.
  int bounded = 0;     ///< Those of them with a cycle bound (records from before it have none).
  double bounded_cycle_s = 0, cycle_bound_s = 0;  ///< Their cycle times and bounds, summed.
  OutcomeCounts outcomes;

  void Add(const ItemResult& item);
  int Count(cell::ItemOutcome outcome) const;
  /// The mean cycle bound of the items that have one, or null.
  std::optional<double> MeanCycleBound() const;
  /// Their cycles over their bounds, or null without bounds.
  std::optional<double> CycleToBound() const;
};

/// The episode summary over `items`: outcome counts, correct-sort rate, recognition accuracy (of the
/// items classified), grasp success rate, mean cycle time of the items that reached a bin.
EpisodeSummary SummarizeEpisode(const std::vector<ItemResult>& items, int attempts, int grasps, const RunFigures& run);
/// The same over items already counted (a sweep's group, counted as its records are read).
EpisodeSummary SummarizeTally(const ItemTally& tally, int attempts, int grasps, const RunFigures& run);
/// The simulated seconds per wall-clock second, or 0 without wall-clock time.
double RealTimeFactor(double sim_time_s, double wall_time_s);

/// a / b, or null when b is 0.
std::optional<double> Ratio(double a, int b);
/// Items sorted per simulated hour, or null without simulated time.
std::optional<double> PicksPerHour(int sorted, double sim_time_s);

/// The one-paragraph summary printed after an episode.
std::string EpisodeParagraph(const EpisodeMetrics& metrics);

void to_json(nlohmann::json& j, const ItemResult& v);
void from_json(const nlohmann::json& j, ItemResult& v);
/// The summary as metrics.json holds it: its figures, the run's flat beside them, the outcome counts and
/// the derived figures. With `pooled_run_only` (a group of episodes pooled into one summary), only the
/// run figures a pool has, and no calibration.
nlohmann::json SummaryJson(const EpisodeSummary& s, bool pooled_run_only);
void to_json(nlohmann::json& j, const EpisodeSummary& v);
void from_json(const nlohmann::json& j, EpisodeSummary& v);
void to_json(nlohmann::json& j, const EpisodeVariation& v);
void to_json(nlohmann::json& j, const CalibrationFigures& v);
void from_json(const nlohmann::json& j, CalibrationFigures& v);
void to_json(nlohmann::json& j, const AttemptLogEntry& v);
/// @throws std::invalid_argument naming the key ("phases[2].hold: missing").
void from_json(const nlohmann::json& j, AttemptLogEntry& v);
void to_json(nlohmann::json& j, const EpisodeMetrics& v);
/// {"sorted": n, ...} in the order of cell::kItemOutcomes.
nlohmann::json OutcomeCountsJson(const OutcomeCounts& counts);

}  // namespace sortcell::simcell

namespace nlohmann {
/// Outcomes and statuses travel as their cell::ToString spellings; an unknown spelling is an error.
template <>
struct adl_serializer<sortcell::cell::ItemOutcome> {
  static void to_json(json& j, sortcell::cell::ItemOutcome v) { j = sortcell::cell::ToString(v); }
  static void from_json(const json& j, sortcell::cell::ItemOutcome& v) {
    v = sortcell::cell::ParseItemOutcome(j.get<std::string>());
  }
};
template <>
struct adl_serializer<sortcell::cell::EpisodeStatus> {
  static void to_json(json& j, sortcell::cell::EpisodeStatus v) { j = sortcell::cell::ToString(v); }
  static void from_json(const json& j, sortcell::cell::EpisodeStatus& v) {
    v = sortcell::cell::ParseEpisodeStatus(j.get<std::string>());
  }
};
}  // namespace nlohmann
