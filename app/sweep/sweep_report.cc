#include "app/sweep/sweep_report.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <numeric>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "files/json_fields.h"
#include "files/output_dir.h"
#include "files/record_fields.h"
#include "simcell/episode_metrics.h"

namespace sortcell::app {
namespace {

// ---- A group of episodes pooled into one summary ----

// The episodes' items, attempts and run figures, pooled as metrics.json's field lists say.
struct Tally {
  int episodes = 0, failed_episodes = 0, attempts = 0, grasps = 0;
  simcell::ItemTally items;
  simcell::RunFigures run;

  void Add(const SweepRecord& record) {
    ++episodes;
    if (!record.ok()) {
      ++failed_episodes;
      return;
    }
    attempts += record.summary.grasp_attempts;
    grasps += record.summary.grasps;
    for (const auto& item : record.items) items.Add(item);
    simcell::PoolRunFigures(run, record.summary.run, record.summary.grasp_attempts);
  }
};

// A group's figures: its episodes summed up as one episode is (simcell::SummarizeEpisode), and what only
// a group has.
struct GroupFigures {
  int episodes = 0, episodes_failed = 0;
  simcell::EpisodeSummary summary;
  std::pair<double, double> ci95{0, 1};  // Of the correct-sort rate.
  simcell::ItemTally items;              // For the unknown objects and the rejections.

  int sorted() const { return summary.outcomes.at(cell::ItemOutcome::kSorted); }
};

// The keys a group has beside its summary's.
struct GroupFiguresFields {
  template <typename Self, typename F>
  static void Visit(Self& f, F&& field) {
    field("episodes", f.episodes);
    field("episodes_failed", f.episodes_failed);
    field("correct_sort_rate_ci95", f.ci95);
  }
};
// Defined, not only declared as records elsewhere are: a function in an unnamed namespace must be (so
// are the other field lists' below).
[[maybe_unused]] GroupFiguresFields RecordFieldsOf(const GroupFigures*) { return {}; }

GroupFigures Figures(const Tally& t) {
  GroupFigures f;
  f.episodes = t.episodes;
  f.episodes_failed = t.failed_episodes;
  simcell::RunFigures run = t.run;
  simcell::FinishRunPool(run, t.attempts);
  f.summary = simcell::SummarizeTally(t.items, t.attempts, t.grasps, run);
  f.ci95 = WilsonInterval(f.sorted(), f.summary.items);
  f.items = t.items;
  return f;
}

// Objects the model does not know (the sweep's unknown set) and the rejections of those it knows.
nlohmann::json RejectionJson(const simcell::ItemTally& t) {
  return {{"unknown_objects", t.unknown},
          {"unknown_rejected", t.unknown_rejected},
          {"unknown_rejected_rate", files::OrNull(simcell::Ratio(t.unknown_rejected, t.unknown))},
          {"unknown_in_category_bin", t.unknown_in_category_bin},
          {"unknown_in_category_bin_rate", files::OrNull(simcell::Ratio(t.unknown_in_category_bin, t.unknown))},
          {"known_objects", t.known},
          {"known_rejected", t.known_rejected},
          {"known_rejected_rate", files::OrNull(simcell::Ratio(t.known_rejected, t.known))}};
}

// summary.json's figures of a group: the pooled summary's keys (metrics.json's), the group's own, and
// the rejections.
nlohmann::json FiguresJson(const GroupFigures& f) {
  nlohmann::json j = simcell::SummaryJson(f.summary, /*pooled_run_only=*/true);
  files::WriteFields(j, f);
  j["rejection"] = RejectionJson(f.items);
  return j;
}

// The outcomes other than sorted (the failures), in metrics.json's order.
std::vector<cell::ItemOutcome> Failures() {
  std::vector<cell::ItemOutcome> failures;
  for (const auto o : cell::kItemOutcomes) {
    if (o != cell::ItemOutcome::kSorted) failures.push_back(o);
  }
  return failures;
}

// ---- Grouping by axis value ----

struct AxisGroup {
  std::string label;
  GroupFigures figures;
};

// The label of a record's value of `axis`: a range axis is cut into 4 equal bins, a model shows its
// file name, a placement its mode, self_calibrate auto, on or off.
std::string ValueLabel(const SweepAxis& axis, const SweepRecord& record) {
  const nlohmann::json& value = record.axes.at(axis.name);
  const bool model = axis.name == "model", text = model || axis.name == "placement" || axis.name == "self_calibrate";
  if (text ? !value.is_string() : !value.is_number()) {
    throw std::invalid_argument("episode " + std::to_string(record.episode) + ": axes." + axis.name + ": expected " +
                                (model  ? "a file name"
                                 : text ? "a text value"
                                        : "a number") +
                                ", found " + value.dump());
  }
  if (model) return std::filesystem::path(value.get<std::string>()).filename().string();
  if (text) return value.get<std::string>();
  if (axis.is_range() && axis.name != "objects" && axis.max > axis.min) {
    const double width = (axis.max - axis.min) / 4;
    // Clamped before the cast: a value from a results file may lie outside the spec's range.
    const int bin = static_cast<int>(std::clamp(std::floor((value.get<double>() - axis.min) / width), 0.0, 3.0));
    return fmt::format("{:.3g}-{:.3g}", axis.min + bin * width, axis.min + (bin + 1) * width);
  }
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  return fmt::format("{:.4g}", value.get<double>());
}

// Numeric labels in numeric order, others in text order.
bool LabelLess(const std::string& a, const std::string& b) {
  try {
    return std::stod(a) < std::stod(b);
  } catch (const std::logic_error&) {
    return a < b;
  }
}

// The records grouped by their value of `axis` (records without it are left out), in label order.
std::vector<AxisGroup> GroupByAxis(const SweepAxis& axis, const std::vector<SweepRecord>& records) {
  std::map<std::string, Tally> tallies;
  std::vector<std::string> order;
  for (const auto& r : records) {
    if (!r.axes.contains(axis.name)) continue;
    const std::string label = ValueLabel(axis, r);
    if (!tallies.count(label)) order.push_back(label);
    tallies[label].Add(r);
  }
  std::sort(order.begin(), order.end(), LabelLess);
  std::vector<AxisGroup> groups;
  for (const auto& label : order) groups.push_back({label, Figures(tallies[label])});
  return groups;
}

// ---- summary.csv ----

// Every figure of a group's JSON as (column, cell): objects flattened with dots ("outcomes.sorted"),
// lists by index ("correct_sort_rate_ci95.0"), null as an empty cell.
void Flatten(const nlohmann::json& j, const std::string& column,
             std::vector<std::pair<std::string, std::string>>& out) {
  const auto inside = [&](const std::string& key) { return column.empty() ? key : column + "." + key; };
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) Flatten(value, inside(key), out);
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) Flatten(j[i], inside(std::to_string(i)), out);
  } else {
    out.emplace_back(column, j.is_null() ? "" : j.is_string() ? files::CsvField(j.get<std::string>()) : j.dump());
  }
}

// One row per group (axis, value, then every figure of summary.json's groups), the columns the union
// of the rows' in the order first met, so that the columns follow from the records' field lists.
class CsvTable {
 public:
  void Add(const std::string& axis, const std::string& value, const nlohmann::json& figures) {
    std::vector<std::pair<std::string, std::string>> cells;
    Flatten(figures, "", cells);
    std::map<std::string, std::string> row{{"axis", files::CsvField(axis)}, {"value", files::CsvField(value)}};
    for (auto& [column, cell] : cells) {
      if (std::find(columns_.begin(), columns_.end(), column) == columns_.end()) columns_.push_back(column);
      row[column] = std::move(cell);
    }
    rows_.push_back(std::move(row));
  }

  std::string Text() const {
    std::string text;
    for (size_t c = 0; c < columns_.size(); ++c) text += (c ? "," : "") + columns_[c];
    text += "\n";
    for (const auto& row : rows_) {
      for (size_t c = 0; c < columns_.size(); ++c) {
        const auto cell = row.find(columns_[c]);
        text += (c ? "," : "") + (cell == row.end() ? std::string() : cell->second);
      }
      text += "\n";
    }
    return text;
  }

 private:
  std::vector<std::string> columns_{"axis", "value"};
  std::vector<std::map<std::string, std::string>> rows_;
};

// ---- summary.md ----

std::string Percent(const std::optional<double>& v) { return v ? fmt::format("{:.1f} %", 100 * *v) : "n/a"; }

// The pick cycle by phase, the phases that cost most first.
std::string MarkdownPhases(const GroupFigures& all) {
  const simcell::RunFigures& run = all.summary.run;
  if (run.cycle_phases_s.empty()) return "";
  std::vector<std::pair<std::string, double>> phases(run.cycle_phases_s.begin(), run.cycle_phases_s.end());
  std::stable_sort(phases.begin(), phases.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  const bool bounded = !run.cycle_phases_bound_s.empty();
  std::string md = std::string("Cycle by phase, mean simulated seconds per attempt") +
                   (bounded ? " (in brackets the arm's least time over the same paths):" : ":");
  for (const auto& [phase, seconds] : phases) {
    const auto bound = run.cycle_phases_bound_s.find(phase);
    md += fmt::format(" {} {:.2f}", phase, seconds) +
          (bound != run.cycle_phases_bound_s.end() ? fmt::format(" ({:.2f}),", bound->second) : ",");
  }
  md.back() = '.';
  md += fmt::format(" Torque-saturated control periods {}, largest tracking error {:.4f} rad.",
                    run.torque_saturated_samples, run.tracking_max_error_rad);
  if (run.carries > 0) {
    md += fmt::format(
        " Held objects slipped {:.2f} mm on average from grasp to bin (largest {:.1f} mm, largest turn"
        " {:.1f} deg).",
        run.carry_slip_sum_mm / run.carries, run.carry_slip_max_mm, run.carry_turn_max_deg);
  }
  return md + "\n\n";
}

std::string MarkdownOverview(const SweepSpec& spec, const GroupFigures& all) {
  std::string md = fmt::format("# Sweep {}\n\n{} episodes ({} failed to run) of {} in the spec, {} items.\n\n",
                               spec.source.filename().string(), all.episodes, all.episodes_failed, spec.EpisodeCount(),
                               all.summary.items);
  md +=
      "| items | correct-sort rate (95 % CI) | recognition accuracy | grasp success | mean cycle per item | "
      "the arm's least time (cycle / it) | picks per hour |\n"
      "|---|---|---|---|---|---|---|\n";
  md +=
      fmt::format("| {} | {} ({:.1f}-{:.1f} %) | {} | {} | {} | {} | {} |\n\n", all.summary.items,
                  Percent(all.summary.correct_sort_rate), 100 * all.ci95.first, 100 * all.ci95.second,
                  Percent(all.summary.recognition_accuracy), Percent(all.summary.grasp_success_rate),
                  all.summary.mean_cycle_time_s ? fmt::format("{:.1f} s", *all.summary.mean_cycle_time_s) : "n/a",
                  all.summary.mean_cycle_bound_s && all.summary.cycle_to_bound
                      ? fmt::format("{:.1f} s (x{:.2f})", *all.summary.mean_cycle_bound_s, *all.summary.cycle_to_bound)
                      : "n/a",
                  all.summary.picks_per_hour ? fmt::format("{:.0f}", *all.summary.picks_per_hour) : "n/a");
  md += MarkdownPhases(all);
  if (all.items.unknown > 0 || all.items.known_rejected > 0) {
    md += fmt::format(
        "Unknown objects: {} of {} rejected ({}), {} sorted into a category bin ({}); known objects wrongly "
        "rejected: {} of {} ({}).\n\n",
        all.items.unknown_rejected, all.items.unknown,
        Percent(simcell::Ratio(all.items.unknown_rejected, all.items.unknown)), all.items.unknown_in_category_bin,
        Percent(simcell::Ratio(all.items.unknown_in_category_bin, all.items.unknown)), all.items.known_rejected,
        all.items.known, Percent(simcell::Ratio(all.items.known_rejected, all.items.known)));
  }
  md += "Outcomes: ";
  for (size_t i = 0; i < cell::kItemOutcomes.size(); ++i) {
    const auto o = cell::kItemOutcomes[i];
    md += fmt::format("{} {}{}", cell::ToString(o), all.summary.outcomes.at(o),
                      i + 1 == cell::kItemOutcomes.size() ? ".\n" : ", ");
  }
  return md;
}

std::string MarkdownAxisTable(const std::string& axis, const std::vector<AxisGroup>& groups) {
  std::string failures;
  for (const auto o : Failures()) {
    std::string name = cell::ToString(o);
    std::replace(name.begin(), name.end(), '_', ' ');
    failures += (failures.empty() ? "" : " / ") + name;
  }
  std::string md = fmt::format(
      "\n## By {0}\n\n| {0} | episodes | items | correct-sort rate | 95 % CI | failures ({1}) "
      "|\n|---|---|---|---|---|---|\n",
      axis, failures);
  for (const auto& g : groups) {
    const GroupFigures& f = g.figures;
    std::string counts;
    for (const auto o : Failures()) counts += (counts.empty() ? "" : " / ") + std::to_string(f.summary.outcomes.at(o));
    md += fmt::format("| {} | {} | {} | {} | {:.1f}-{:.1f} % | {} |\n", g.label, f.episodes, f.summary.items,
                      Percent(f.summary.correct_sort_rate), 100 * f.ci95.first, 100 * f.ci95.second, counts);
  }
  return md;
}

// ---- plot_<axis>.png ----

// The correct-sort rate by axis value with its 95 % interval, drawn by gnuplot (if installed).
void Plot(const std::filesystem::path& dir, const std::string& axis, const std::vector<AxisGroup>& groups) {
  const std::filesystem::path data = dir / ("plot_" + axis + ".dat");
  std::string rows;
  for (size_t i = 0; i < groups.size(); ++i) {
    const GroupFigures& f = groups[i].figures;
    if (!f.summary.correct_sort_rate) continue;
    std::string label = groups[i].label;
    std::replace(label.begin(), label.end(), '"', '\'');
    rows += fmt::format("{} \"{}\" {} {} {}\n", i, label, 100 * *f.summary.correct_sort_rate, 100 * f.ci95.first,
                        100 * f.ci95.second);
  }
  files::WriteTextFile(data, rows);
  const std::filesystem::path png = dir / ("plot_" + axis + ".png");
  const std::string script = fmt::format(
      "set terminal pngcairo size 800,500\nset output '{0}'\nset title 'Correct-sort rate by {1} (95% CI)'\n"
      "set ylabel 'items in the correct bin (%)'\nset xlabel '{1}'\nset yrange [0:105]\nset grid ytics\n"
      "set xrange [-0.5:{2:.1f}]\nset key off\n"
      "plot '{3}' using 1:3:4:5:xticlabels(2) with yerrorbars pt 7 ps 1.5 lw 2\n",
      png.string(), axis, groups.size() - 0.5, data.string());
  FILE* gnuplot = popen("gnuplot 2>/dev/null", "w");
  if (gnuplot != nullptr) {
    std::fputs(script.c_str(), gnuplot);
    if (pclose(gnuplot) != 0) spdlog::warn("gnuplot could not draw {} (is gnuplot installed?)", png.string());
  }
  std::error_code ec;
  std::filesystem::remove(data, ec);
}

}  // namespace

std::pair<double, double> WilsonInterval(int successes, int n) {
  if (n <= 0) return {0.0, 1.0};
  const double z = 1.959963984540054, p = static_cast<double>(successes) / n;
  const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / (1 + z * z / n);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

namespace {

// The items grouped by object (the set's names), in name order: which objects fail, and how.
std::vector<AxisGroup> GroupByObject(const std::vector<SweepRecord>& records) {
  std::map<std::string, Tally> tallies;
  for (const auto& r : records) {
    if (!r.ok()) continue;
    std::set<std::string> in_episode;
    for (const auto& item : r.items) {
      tallies[item.name].items.Add(item);
      if (in_episode.insert(item.name).second) ++tallies[item.name].episodes;
    }
  }
  std::vector<AxisGroup> groups;
  for (const auto& [name, tally] : tallies) groups.push_back({name, Figures(tally)});
  return groups;
}

// The categories whose recognition the sweep checked on one object only (every item of the category,
// unknown objects aside, was the same object): a set with a single instance of a category, or a sweep
// too short to draw the others.
std::vector<std::string> SingleInstanceCategories(const std::vector<SweepRecord>& records) {
  std::map<std::string, std::set<std::string>> objects;
  for (const auto& r : records) {
    for (const auto& item : r.items) {
      if (!item.unknown) objects[item.true_category].insert(item.name);
    }
  }
  std::vector<std::string> single;
  for (const auto& [category, names] : objects) {
    if (names.size() == 1) single.push_back(category + " (" + *names.begin() + ")");
  }
  return single;
}

// The upper median and the largest of values (not empty).
double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
double Largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

// The episodes' hand-eye self-calibrations (summary.json's "calibration"): how many succeeded, the
// camera error they left (median and largest) against the nominal pose's, and what they cost.
struct CalibrationPool {
  int episodes = 0, ok = 0;
  double median_error_m = 0, max_error_m = 0, median_error_rad = 0, max_error_rad = 0;
  double max_prior_error_m = 0, max_prior_error_rad = 0, mean_duration_s = 0;
};
struct CalibrationPoolFields {
  template <typename Self, typename F>
  static void Visit(Self& c, F&& field) {
    field("episodes", c.episodes);
    field("ok", c.ok);
    field("median_error_m", c.median_error_m);
    field("max_error_m", c.max_error_m);
    field("median_error_rad", c.median_error_rad);
    field("max_error_rad", c.max_error_rad);
    field("max_prior_error_m", c.max_prior_error_m);
    field("max_prior_error_rad", c.max_prior_error_rad);
    field("mean_duration_s", c.mean_duration_s);
  }
};
[[maybe_unused]] CalibrationPoolFields RecordFieldsOf(const CalibrationPool*) { return {}; }

std::optional<CalibrationPool> PoolCalibrations(const std::vector<SweepRecord>& records) {
  std::vector<double> error_m, error_rad, prior_m, prior_rad, duration_s;
  CalibrationPool pool;
  for (const auto& r : records) {
    if (!r.ok() || !r.summary.calibration) continue;
    const simcell::CalibrationFigures& c = *r.summary.calibration;
    pool.ok += c.status == "ok";
    error_m.push_back(c.error_m), error_rad.push_back(c.error_rad);
    prior_m.push_back(c.prior_error_m), prior_rad.push_back(c.prior_error_rad);
    duration_s.push_back(c.duration_s);
  }
  if (error_m.empty()) return std::nullopt;  // No episode calibrated: null.
  pool.episodes = static_cast<int>(error_m.size());
  pool.median_error_m = Median(error_m), pool.max_error_m = Largest(error_m);
  pool.median_error_rad = Median(error_rad), pool.max_error_rad = Largest(error_rad);
  pool.max_prior_error_m = Largest(prior_m), pool.max_prior_error_rad = Largest(prior_rad);
  pool.mean_duration_s = std::accumulate(duration_s.begin(), duration_s.end(), 0.0) / duration_s.size();
  return pool;
}

nlohmann::json CalibrationJson(const std::optional<CalibrationPool>& pool) {
  if (!pool) return nullptr;
  nlohmann::json j;
  files::WriteFields(j, *pool);
  return j;
}

std::string MarkdownCalibration(const std::optional<CalibrationPool>& c) {
  if (!c) return "";
  return fmt::format(
      "\nSelf-calibration in {} episodes ({} ok): camera error median {:.2f} mm / {:.4f} rad, largest {:.2f} mm / "
      "{:.4f} rad (the nominal pose's largest: {:.1f} mm / {:.4f} rad); {:.1f} simulated s each.\n",
      c->episodes, c->ok, 1000 * c->median_error_m, c->median_error_rad, 1000 * c->max_error_m, c->max_error_rad,
      1000 * c->max_prior_error_m, c->max_prior_error_rad, c->mean_duration_s);
}

// How the workers ended (by status, with the episodes that did not end ok), and what they used.
nlohmann::json RunsSummary(const std::vector<SweepRecord>& records) {
  std::map<std::string, int> by_status;
  for (const auto& [status, name] : kRunStatusNames) by_status[name] = 0;
  nlohmann::json failed = nlohmann::json::array();
  for (const auto& r : records) {
    ++by_status[ToString(r.status)];
    if (!r.ok())
      failed.push_back({{"episode", r.episode}, {"status", ToString(r.status)}, {"error", r.error.value_or("")}});
  }
  nlohmann::json runs = by_status;
  runs["not_ok"] = failed;
  return runs;
}

// The median and the largest of some figures.
struct Spread {
  double median = 0, max = 0;
};
struct SpreadFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("median", v.median);
    field("max", v.max);
  }
};
[[maybe_unused]] SpreadFields RecordFieldsOf(const Spread*) { return {}; }

std::optional<Spread> SpreadOf(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return Spread{Median(values), Largest(values)};
}

// The machine's figures (summary.json's "resources"): peak memory per worker and wall time per episode.
struct Resources {
  std::optional<Spread> worker_peak_memory_mb, episode_wall_time_s;
};

Resources ResourcesOf(const std::vector<SweepRecord>& records) {
  std::vector<double> memory_mb, wall_s;
  for (const auto& r : records) {
    if (r.peak_memory_mb) memory_mb.push_back(*r.peak_memory_mb);
    wall_s.push_back(r.wall_time_s);
  }
  return {SpreadOf(memory_mb), SpreadOf(wall_s)};
}

nlohmann::json ResourcesJson(const Resources& r) {
  nlohmann::json j = nlohmann::json::object();
  // Keys only for what was measured (results from before the memory was recorded have none).
  const auto put = [&](const char* key, const std::optional<Spread>& spread) {
    if (spread) files::WriteFields(j[key], *spread);
  };
  put("worker_peak_memory_mb", r.worker_peak_memory_mb);
  put("episode_wall_time_s", r.episode_wall_time_s);
  return j;
}

std::string MarkdownRuns(const nlohmann::json& runs, const Resources& resources) {
  std::string md = "Worker runs:";
  for (const auto& [status, name] : kRunStatusNames) md += fmt::format(" {} {},", name, runs[name].get<int>());
  md.pop_back();
  for (const auto& f : runs["not_ok"]) {
    md += fmt::format("; episode {} {} ({})", f["episode"].get<int>(), f["status"].get<std::string>(),
                      f["error"].get<std::string>());
  }
  md += ".";
  if (const auto& m = resources.worker_peak_memory_mb) {
    md += fmt::format(" Peak memory per worker: median {:.0f} MiB, largest {:.0f} MiB.", m->median, m->max);
  }
  return md + "\n\n";
}

}  // namespace

nlohmann::json WriteSweepReport(const std::filesystem::path& dir, const SweepSpec& spec,
                                const std::vector<SweepRecord>& in_any_order) {
  // In episode order: sums of floating-point figures then do not depend on the order the episodes
  // finished in (shards merged give the unsharded run's summary, to the last bit).
  std::vector<SweepRecord> records = in_any_order;
  std::stable_sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.episode < b.episode; });
  Tally tally;
  for (const auto& r : records) tally.Add(r);
  const GroupFigures all = Figures(tally);
  nlohmann::json summary = FiguresJson(all);
  CsvTable csv;
  csv.Add("all", "all", summary);
  summary["spec"] = spec.source.string();
  summary["episodes_in_spec"] = spec.EpisodeCount();
  nlohmann::json by_axis = nlohmann::json::object();
  std::string md = MarkdownOverview(spec, all);
  summary["runs"] = RunsSummary(records);
  const Resources resources = ResourcesOf(records);
  summary["resources"] = ResourcesJson(resources);
  md += MarkdownRuns(summary["runs"], resources);
  const std::optional<CalibrationPool> calibration = PoolCalibrations(records);
  summary["calibration"] = CalibrationJson(calibration);
  md += MarkdownCalibration(calibration);
  summary["single_instance_categories"] = SingleInstanceCategories(records);
  if (!summary["single_instance_categories"].empty()) {
    std::string list;
    for (const auto& c : summary["single_instance_categories"])
      list += (list.empty() ? "" : ", ") + c.get<std::string>();
    md += "\nRecognition of " + list +
          " was checked on that one object only: no other object of its category took part.\n";
  }
  for (const auto& axis : spec.axes) {
    const std::vector<AxisGroup> groups = GroupByAxis(axis, records);
    if (groups.size() < 2) continue;
    for (const auto& g : groups) {
      const nlohmann::json figures = FiguresJson(g.figures);
      by_axis[axis.name][g.label] = figures;
      csv.Add(axis.name, g.label, figures);
    }
    md += MarkdownAxisTable(axis.name, groups);
    Plot(dir, axis.name, groups);
    md += "\n![correct-sort rate by " + axis.name + "](plot_" + axis.name + ".png)\n";
  }
  summary["by_axis"] = by_axis;
  nlohmann::json by_object = nlohmann::json::object();
  const std::vector<AxisGroup> objects = GroupByObject(records);
  for (const auto& g : objects) {
    const nlohmann::json figures = FiguresJson(g.figures);
    by_object[g.label] = figures;
    csv.Add("object", g.label, figures);
  }
  if (!objects.empty()) md += MarkdownAxisTable("object", objects);
  summary["by_object"] = by_object;
  files::WriteTextFile(dir / "summary.csv", csv.Text());
  files::WriteTextFile(dir / "summary.md", md);
  files::WriteJson(dir / "summary.json", summary);
  return summary;
}

}  // namespace sortcell::app
