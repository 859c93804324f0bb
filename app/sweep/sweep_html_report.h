#pragma once
/// @file
/// `sortcell report DIR` (and `sweep --report`, `sweep --review`): DIR/report/index.html, one page per
/// sweep folder that opens offline from the file system: the summary, the correct-sort rate by axis value
/// and by object and the cycle by phase (Chart.js, from Debian's libjs-chart.js, copied beside the page
/// with its licence), a table of every episode that sorts and filters by outcome, object and axis value,
/// and every failed item (with `--review`: its attempts in words and its clip).

#include <filesystem>

#include <nlohmann/json.hpp>

namespace sortcell::app {

/// Where Chart.js is installed (Debian's libjs-chart.js); $SORTCELL_CHART_JS overrides it.
std::filesystem::path ChartJsFile();

/// The data the page shows: {name, summary, episodes: [{episode, seed, axes, status, items: [[name,
/// outcome], ...]}], review (review.json or null)}.
/// @throws std::invalid_argument naming the folder when it has no summary.json or results.jsonl, or a
///         damaged line in results.jsonl.
nlohmann::json ReportData(const std::filesystem::path& dir);

/// The page with `data` in it (every '<' of the JSON written \u003c, so that no value can end its script
/// or change how the HTML parser reads it).
/// @throws std::runtime_error if the template (web/sweep_report.html under the data folder) is missing.
std::string ReportPage(const nlohmann::json& data);

/// Writes DIR/report/index.html, chart.min.js and CHART_JS_LICENSE; returns the page's path. Without
/// Chart.js installed the page still opens, saying it has no plots (and a warning is logged).
/// @throws as ReportData and ReportPage, and std::runtime_error if a file cannot be written.
std::filesystem::path WriteHtmlReport(const std::filesystem::path& dir);

}  // namespace sortcell::app
