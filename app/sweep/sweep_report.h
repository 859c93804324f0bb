#pragma once
/// @file
/// The summary of a sweep's results: summary.json (totals, outcome counts, rates with 95 % Wilson
/// intervals, by axis value), summary.csv and summary.md (correct-sort rate by axis value) and one
/// PNG plot per varied axis (gnuplot).

#include <filesystem>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_spec.h"

namespace sortcell::app {

/// 95 % Wilson score interval of `successes` out of `n` ({0, 1} for n = 0).
std::pair<double, double> WilsonInterval(int successes, int n);

/// Writes the summary files into `dir` from the records of results.jsonl; returns summary.json.
/// Every write is checked. (A missing gnuplot only costs the plots, with a warning.)
/// @throws std::runtime_error "cannot write '<file>'" if a summary file cannot be written.
/// @throws std::invalid_argument "episode <n>: axes.<name>: expected ..." for a record whose value
///         of a varied axis has the wrong type.
nlohmann::json WriteSweepReport(const std::filesystem::path& dir, const SweepSpec& spec,
                                const std::vector<SweepRecord>& in_any_order);

}  // namespace sortcell::app
