#pragma once
/// @file
/// `sortcell sweep --review`: every episode of a sweep with a failed item is replayed with its review
/// video (sweep_replay.h), and for each failed item the moment it failed is found in the episode's
/// attempt log, told in words, and a clip of a few seconds around it is cut from the video. Written to
/// DIR/review.json for the report; the clips and replays lie in DIR/replays/<episode>/.

#include <cstdint>
#include <optional>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simcell/episode_metrics.h"

namespace sortcell::app {

/// One attempt (or a cluster left alone) in words: "attempt 2 at 31.4-36.0 s: called cup (0.91) for
/// bin cup; closed at 41 mm on a 71 mm wide view; dropped during carry at 34.2 s".
std::string AttemptInWords(const simcell::AttemptLogEntry& attempt, int number);

/// A failed item of one episode: when it failed (simulated seconds) and what the cell did about it.
struct ItemFailure {
  std::string item;
  cell::ItemOutcome outcome = cell::ItemOutcome::kLeftOnTable;
  double at_s = 0;
  /// When the cell last decided about it (its last attempt began, or it was left alone); null when it
  /// never did.
  std::optional<double> decided_at_s;
  std::vector<std::string> log;  ///< The item's attempts in words, in order (or why it never had one).
};

/// The failed items of an episode (every item not sorted), from its metrics: an item's attempts are
/// those whose detection was that object (the scorer's truth_object); it failed when its last attempt
/// ended, or, if it was dropped, when the gripper found itself empty; an item never attempted failed
/// when the cell last looked at it and left it (a skipped cluster where it lies, within 5 cm), else at
/// the episode's end.
std::vector<ItemFailure> FailuresOf(const std::vector<simcell::ItemResult>& items,
                                    const std::vector<simcell::AttemptLogEntry>& attempts, double episode_end_s);

struct ReviewedFailure {
  int episode = 0;
  uint64_t seed = 0;
  nlohmann::json axes;
  ItemFailure failure;
  std::string clip;  ///< Relative to the sweep folder; empty when none could be cut.
  /// The Kinect still of the last decision about it (relative), or, for an item never decided about, of
  /// the cell's last look before it failed; empty when none.
  std::string still;
};

struct SweepReview {
  std::vector<ReviewedFailure> failures;
  int episodes_replayed = 0;
  /// Replays whose record did not match the sweep's ("episode 4: /items/0/outcome: ..."); their clips
  /// still show what the replay did.
  std::vector<std::string> mismatches;
  /// Episodes that could not be replayed ("episode 4: <why>": another build, a changed model, a record
  /// from before replays, a replay that failed); the rest are reviewed all the same.
  std::vector<std::string> not_replayed;
};

/// Replays each episode of `dir` with a failed item (with video and stills), cuts a clip of `before_s` +
/// `after_s` around each failure and writes DIR/review.json. Episodes that crashed or timed out are not
/// replayed; one that cannot be replayed is listed in `not_replayed` and the review goes on.
/// @throws as ReadSweepFolder, and std::runtime_error if review.json cannot be written.
SweepReview ReviewSweep(const std::filesystem::path& dir, double before_s = 3, double after_s = 3);

nlohmann::json ReviewJson(const SweepReview& review);

}  // namespace sortcell::app
