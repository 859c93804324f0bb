#pragma once
/// @file
/// The expected outcomes of a sorting episode as values: how one pick attempt ended, what became of
/// each item, why the episode stopped. Their spellings in metrics.json, the sweep's records and the
/// CLI are defined here and nowhere else.

#include <array>
#include <string>
#include <string_view>

namespace sortcell::cell {

/// How one pick-and-place attempt ended, as the cell's sensors tell it.
enum class AttemptResult {
  kReleased,      ///< Held above the bin and released into it.
  kMissed,        ///< The fingers closed on nothing.
  kDropped,       ///< Lost after the lift or during the carry.
  kPutBack,       ///< Lifted, but its bin cannot be reached from here: put back where it was.
  kMotionFailed,  ///< A motion on the way could not be planned (unreachable, singular).
  kSimDiverged,   ///< The cell stopped under a motion.
};

/// What became of an item at the end of an episode (scored from the simulator's ground truth).
/// kUngraspable: wider than the gripper's stroke in every direction, as the cloud shows it (e.g. a
/// cereal box lying on its face): left on the table, never attempted.
enum class ItemOutcome {
  kSorted,
  kWrongBin,
  kDropped,
  kGraspFailed,
  kUnreachable,
  kNotDetected,
  kLeftOnTable,
  kUngraspable
};
inline constexpr std::array<ItemOutcome, 8> kItemOutcomes{
    ItemOutcome::kSorted,      ItemOutcome::kWrongBin,    ItemOutcome::kDropped,     ItemOutcome::kGraspFailed,
    ItemOutcome::kUnreachable, ItemOutcome::kNotDetected, ItemOutcome::kLeftOnTable, ItemOutcome::kUngraspable};

/// Why an episode ended.
enum class EpisodeStatus {
  kCompleted,     ///< Nothing pickable left in view.
  kTimeLimit,     ///< The time budget ran out.
  kAttemptLimit,  ///< The attempt budget ran out.
  kSimDiverged,   ///< The cell stopped under a motion.
};

/// "released", "missed", "dropped", "put_back", "motion_failed", "sim_diverged".
const char* ToString(AttemptResult result);
/// "sorted", "wrong_bin", "dropped", "grasp_failed", "unreachable", "not_detected", "left_on_table",
/// "ungraspable".
const char* ToString(ItemOutcome outcome);
/// "completed", "time_limit", "attempt_limit", "sim_diverged".
const char* ToString(EpisodeStatus status);

/// The inverse of ToString.
/// @throws std::invalid_argument "unknown <what> '<text>' (expected a, b or c)".
AttemptResult ParseAttemptResult(std::string_view text);
ItemOutcome ParseItemOutcome(std::string_view text);
EpisodeStatus ParseEpisodeStatus(std::string_view text);

}  // namespace sortcell::cell
