#pragma once
/// @file
/// The summary of a sweep's results: summary.json (totals, outcome counts, rates with 95 % Wilson
/// intervals, by axis value), summary.csv and summary.md (correct-sort rate by axis value) and one
/// PNG plot per varied axis (gnuplot).

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep_spec.h"

namespace sortcell::app {

/// 95 % Wilson score interval of `successes` out of `n` ({0, 1} for n = 0).
std::pair<double, double> WilsonInterval(int successes, int n);

/// Writes the summary files into `dir` from the records of results.jsonl; returns summary.json.
nlohmann::json WriteSweepReport(const std::filesystem::path& dir, const SweepSpec& spec,
                                const std::vector<nlohmann::json>& records);

}  // namespace sortcell::app
