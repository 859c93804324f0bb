#pragma once
/// @file
/// `sortcell compare A B`: two sweep folders of the same episodes (a change's before and after). The
/// episodes are paired by index (their seeds and axis values must agree), their items by name, so the
/// test of the difference is a paired one: the exact McNemar test on the items sorted in one sweep
/// and not in the other. Episodes that crashed or timed out in either sweep pair nothing.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep/sweep_record.h"
#include "cell/outcomes.h"

namespace sortcell::app {

/// A correct-sort rate with its 95 % Wilson interval.
struct SortRate {
  int sorted = 0, items = 0;
  double rate = 0, low = 0, high = 1;  ///< rate 0 and {0, 1} for no items.
};

/// An item whose outcome differs between the two sweeps.
struct ItemChange {
  int episode = 0;
  uint64_t seed = 0;
  nlohmann::json axes;
  std::string item;
  cell::ItemOutcome before = cell::ItemOutcome::kSorted, after = cell::ItemOutcome::kSorted;
};

struct SweepComparison {
  SortRate a, b;                       ///< Each over all of its sweep's items (as its summary counts them).
  int episodes_paired = 0;             ///< Ran to the end in both.
  std::vector<int> episodes_unpaired;  ///< In one sweep only, or crashed / timed out in either.
  int items_paired = 0;
  int items_unpaired = 0;                          ///< In a paired episode of one sweep only.
  int sorted_only_in_a = 0, sorted_only_in_b = 0;  ///< The discordant pairs.
  double p_value = 1;                              ///< Exact McNemar test, two-sided (1 when no pair differs).
  bool significant = false;                        ///< p_value < 0.05.
  std::vector<ItemChange> changed;                 ///< Every paired item whose outcome differs, by episode then name.
  /// The folders' spec.yaml differ (other --set overrides, e.g. two models, or an edited spec): said, not
  /// refused, since the episodes are checked one by one.
  bool specs_differ = false;
};

/// Two-sided exact McNemar p-value for `b` and `c` discordant pairs: twice the binomial(b + c, 1/2)
/// tail of min(b, c), at most 1.
double ExactMcNemarP(int b, int c);

/// Compares the records of two sweeps.
/// @throws std::invalid_argument "episode <n>: seed <s> in A, <t> in B: not the same episodes" (or
///         the same for its axes) when an episode index means different episodes. Axis noise_seed may
///         differ: other draws of the Kinect's noise over the same scenes.
SweepComparison CompareSweepRecords(const std::vector<SweepRecord>& a, const std::vector<SweepRecord>& b);

/// Reads `<dir>/results.jsonl` of both folders and compares them.
/// @throws std::invalid_argument as ReadSweepFolder (a damaged line's episode would be missing from the
///         pairing) and as CompareSweepRecords.
SweepComparison CompareSweepFolders(const std::filesystem::path& a, const std::filesystem::path& b);

/// The comparison in words, for the terminal: both rates, the paired test and its verdict, then each
/// changed item ("episode 3 (seed 3, objects=5): mug: dropped -> sorted").
std::string ComparisonText(const SweepComparison& c, const std::filesystem::path& a, const std::filesystem::path& b);

/// compare.json: the figures, the changed items and both folders.
nlohmann::json ComparisonJson(const SweepComparison& c, const std::filesystem::path& a, const std::filesystem::path& b);

/// A self-contained HTML page of the comparison (no scripts, no network), each changed item linked
/// (relative to `page_dir`) in both sweeps to its failure or its episode on the sweep's report page
/// (`sortcell report`), else to the episode's metrics.json where the sweep kept it.
std::string ComparisonHtml(const SweepComparison& c, const std::filesystem::path& a, const std::filesystem::path& b,
                           const std::filesystem::path& page_dir);

}  // namespace sortcell::app
