#include "app/sweep/sweep_html_report.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "files/data_dir.h"
#include "files/output_dir.h"
#include "app/sweep/sweep_record.h"

namespace sortcell::app {
namespace {

constexpr const char* kPlaceholder = "/*SORTCELL_DATA*/";
constexpr const char* kChartLicence = "/usr/share/doc/libjs-chart.js/copyright";

nlohmann::json EpisodeRow(const SweepRecord& r) {
  nlohmann::json items = nlohmann::json::array();
  for (const auto& item : r.items) items.push_back({item.name, cell::ToString(item.outcome)});
  return {{"episode", r.episode}, {"seed", r.seed}, {"axes", r.axes}, {"status", ToString(r.status)}, {"items", items}};
}

nlohmann::json ReadJsonFile(const std::filesystem::path& file) {
  try {
    return nlohmann::json::parse(files::ReadTextFile(file));
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument("'" + file.string() + "': not JSON (" + e.what() + ")");
  }
}

// Copies `from` to `to` checked; false (with a warning) when `from` is not there.
bool CopyIfThere(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(from, ec)) {
    spdlog::warn("report: {} is missing (Debian's libjs-chart.js): the page will have no plots", from.string());
    return false;
  }
  files::WriteTextFile(to, files::ReadTextFile(from));
  return true;
}

}  // namespace

std::filesystem::path ChartJsFile() {
  const char* file = std::getenv("SORTCELL_CHART_JS");
  return file && *file ? file : "/usr/share/javascript/chart.js/chart.min.js";
}

nlohmann::json ReportData(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(dir / "summary.json", ec)) {
    throw std::invalid_argument("'" + dir.string() + "': not a finished sweep folder (no summary.json)");
  }
  nlohmann::json episodes = nlohmann::json::array();
  for (const auto& r : ReadSweepFolder(dir)) episodes.push_back(EpisodeRow(r));
  std::sort(episodes.begin(), episodes.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a["episode"] < b["episode"]; });
  const std::filesystem::path review = dir / "review.json";
  std::filesystem::path named = std::filesystem::absolute(dir).lexically_normal();
  if (named.filename().empty()) named = named.parent_path();  // "DIR/" and "." name the folder too.
  return {{"name", named.filename().string()},
          {"summary", ReadJsonFile(dir / "summary.json")},
          {"episodes", episodes},
          {"review", std::filesystem::exists(review, ec) ? ReadJsonFile(review) : nlohmann::json(nullptr)}};
}

std::string ReportPage(const nlohmann::json& data) {
  std::string page = files::ReadTextFile(std::filesystem::path(files::DataDir()) / "web/sweep_report.html");
  const size_t at = page.find(kPlaceholder);
  if (at == std::string::npos) throw std::runtime_error("report template: no " + std::string(kPlaceholder) + " in it");
  // Every '<' as \u003c (inside JSON strings, the only place one can be): no "</script>" and no "<!--"
  // can change how the HTML parser reads the data's script element.
  std::string json;
  for (char c : data.dump()) {
    if (c == '<') {
      json += "\\u003c";
    } else {
      json += c;
    }
  }
  return page.replace(at, std::string(kPlaceholder).size(), json);
}

std::filesystem::path WriteHtmlReport(const std::filesystem::path& dir) {
  const nlohmann::json data = ReportData(dir);
  const std::filesystem::path report = dir / "report";
  std::filesystem::create_directories(report);
  if (CopyIfThere(ChartJsFile(), report / "chart.min.js")) {
    std::error_code ec;
    if (std::filesystem::exists(kChartLicence, ec))
      files::WriteTextFile(report / "CHART_JS_LICENSE", files::ReadTextFile(kChartLicence));
  }
  files::WriteTextFile(report / "index.html", ReportPage(data));
  return report / "index.html";
}

}  // namespace sortcell::app
