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

// ---- Totals over a group of episodes ----

struct Tally {
  int episodes = 0, failed_episodes = 0, attempts = 0, grasps = 0;
  double sim_s = 0, wall_s = 0;
  simcell::ItemTally items;
  std::map<std::string, double> phase_s;        // Simulated seconds in each pick phase, over every attempt.
  std::map<std::string, double> phase_bound_s;  // The arm's least time in each, over every attempt.
  int saturated = 0;
  double max_error = 0;
  double slip_max_mm = 0, slip_sum_mm = 0, turn_max_deg = 0;
  int carries = 0;

  void Add(const SweepRecord& record) {
    ++episodes;
    if (!record.ok()) {
      ++failed_episodes;
      return;
    }
    attempts += record.summary.grasp_attempts;
    grasps += record.summary.grasps;
    sim_s += record.summary.run.sim_time_s;
    wall_s += record.summary.run.wall_time_s;
    for (const auto& item : record.items) items.Add(item);
    const simcell::RunFigures& run = record.summary.run;
    for (const auto& [phase, mean_s] : run.cycle_phases_s) phase_s[phase] += mean_s * record.summary.grasp_attempts;
    for (const auto& [phase, mean_s] : run.cycle_phases_bound_s) {
      phase_bound_s[phase] += mean_s * record.summary.grasp_attempts;
    }
    saturated += run.torque_saturated_samples;
    max_error = std::max(max_error, run.tracking_max_error_rad);
    slip_max_mm = std::max(slip_max_mm, run.carry_slip_max_mm);
    slip_sum_mm += run.carry_slip_sum_mm;
    turn_max_deg = std::max(turn_max_deg, run.carry_turn_max_deg);
    carries += run.carries;
  }
};

// A group's figures, as summary.json, summary.csv and summary.md show them.
struct GroupFigures {
  int episodes = 0, episodes_failed = 0, items = 0, sorted = 0, grasp_attempts = 0;
  std::optional<double> correct_sort_rate, recognition_accuracy, grasp_success_rate, mean_cycle_time_s,
      real_time_factor;
  std::optional<double> picks_per_hour, mean_cycle_bound_s, cycle_to_bound;
  std::map<std::string, double> cycle_phases_s;        // Mean simulated seconds per attempt in each phase.
  std::map<std::string, double> cycle_phases_bound_s;  // The arm's least time per attempt in each phase.
  int torque_saturated_samples = 0;
  double tracking_max_error_rad = 0;
  double carry_slip_max_mm = 0, carry_turn_max_deg = 0;
  std::optional<double> carry_slip_mean_mm;
  std::pair<double, double> ci95{0, 1};
  simcell::OutcomeCounts outcomes;
  double sim_time_s = 0, episode_wall_time_s = 0;
  int unknown = 0, unknown_rejected = 0, unknown_in_category_bin = 0, known = 0, known_rejected = 0;
};

GroupFigures Figures(const Tally& t) {
  GroupFigures f;
  f.episodes = t.episodes;
  f.episodes_failed = t.failed_episodes;
  f.items = t.items.items;
  f.sorted = t.items.Count(cell::ItemOutcome::kSorted);
  f.correct_sort_rate = simcell::Ratio(f.sorted, f.items);
  f.ci95 = WilsonInterval(f.sorted, f.items);
  for (const auto outcome : cell::kItemOutcomes) f.outcomes[outcome] = t.items.Count(outcome);
  f.recognition_accuracy = simcell::Ratio(t.items.recognised, t.items.classified);
  f.grasp_success_rate = simcell::Ratio(t.grasps, t.attempts);
  f.grasp_attempts = t.attempts;
  f.mean_cycle_time_s = simcell::Ratio(t.items.cycle_s, t.items.completed);
  f.mean_cycle_bound_s = t.items.MeanCycleBound();
  f.cycle_to_bound = t.items.CycleToBound();
  f.sim_time_s = t.sim_s;
  f.episode_wall_time_s = t.wall_s;
  if (t.wall_s > 0) f.real_time_factor = t.sim_s / t.wall_s;
  f.picks_per_hour = simcell::PicksPerHour(f.sorted, t.sim_s);
  if (t.attempts > 0) {
    for (const auto& [phase, seconds] : t.phase_s) f.cycle_phases_s[phase] = seconds / t.attempts;
    for (const auto& [phase, seconds] : t.phase_bound_s) f.cycle_phases_bound_s[phase] = seconds / t.attempts;
  }
  f.torque_saturated_samples = t.saturated;
  f.tracking_max_error_rad = t.max_error;
  f.carry_slip_max_mm = t.slip_max_mm;
  f.carry_slip_mean_mm = simcell::Ratio(t.slip_sum_mm, t.carries);
  f.carry_turn_max_deg = t.turn_max_deg;
  f.unknown = t.items.unknown;
  f.unknown_rejected = t.items.unknown_rejected;
  f.unknown_in_category_bin = t.items.unknown_in_category_bin;
  f.known = t.items.known;
  f.known_rejected = t.items.known_rejected;
  return f;
}

// Objects the model does not know (the sweep's unknown set) and the rejections of those it knows.
nlohmann::json RejectionJson(const GroupFigures& f) {
  return {{"unknown_objects", f.unknown},
          {"unknown_rejected", f.unknown_rejected},
          {"unknown_rejected_rate", files::OrNull(simcell::Ratio(f.unknown_rejected, f.unknown))},
          {"unknown_in_category_bin", f.unknown_in_category_bin},
          {"unknown_in_category_bin_rate", files::OrNull(simcell::Ratio(f.unknown_in_category_bin, f.unknown))},
          {"known_objects", f.known},
          {"known_rejected", f.known_rejected},
          {"known_rejected_rate", files::OrNull(simcell::Ratio(f.known_rejected, f.known))}};
}

// summary.json's keys of a group (the outcome counts and the rejection figures beside them).
struct GroupFiguresFields {
  template <typename Self, typename F>
  static void Visit(Self& f, F&& field) {
    field("episodes", f.episodes);
    field("episodes_failed", f.episodes_failed);
    field("items", f.items);
    field("correct_sort_rate", f.correct_sort_rate);
    field("correct_sort_rate_ci95", f.ci95);
    field("recognition_accuracy", f.recognition_accuracy);
    field("grasp_success_rate", f.grasp_success_rate);
    field("grasp_attempts", f.grasp_attempts);
    field("mean_cycle_time_s", f.mean_cycle_time_s);
    field("mean_cycle_bound_s", f.mean_cycle_bound_s);
    field("cycle_to_bound", f.cycle_to_bound);
    field("picks_per_hour", f.picks_per_hour);
    field("cycle_phases_s", f.cycle_phases_s);
    field("cycle_phases_bound_s", f.cycle_phases_bound_s);
    field("torque_saturated_samples", f.torque_saturated_samples);
    field("tracking_max_error_rad", f.tracking_max_error_rad);
    field("carry_slip_max_mm", f.carry_slip_max_mm);
    field("carry_slip_mean_mm", f.carry_slip_mean_mm);
    field("carry_turn_max_deg", f.carry_turn_max_deg);
    field("sim_time_s", f.sim_time_s);
    field("episode_wall_time_s", f.episode_wall_time_s);
    field("real_time_factor", f.real_time_factor);
  }
};
// Defined, not only declared (as records elsewhere do): a function in an unnamed namespace must be.
[[maybe_unused]] GroupFiguresFields RecordFieldsOf(const GroupFigures*) { return {}; }

nlohmann::json FiguresJson(const GroupFigures& f) {
  nlohmann::json j;
  files::WriteFields(j, f);
  j["outcomes"] = simcell::OutcomeCountsJson(f.outcomes);
  j["rejection"] = RejectionJson(f);
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

std::string Number(double v) { return nlohmann::json(v).dump(); }

std::string CsvHeader() {
  std::string header = "axis,value,episodes,items,sorted,correct_sort_rate,ci95_low,ci95_high";
  for (const auto o : Failures()) header += std::string(",") + cell::ToString(o);
  return header + ",episodes_failed\n";
}

std::string CsvRow(const std::string& axis, const std::string& value, const GroupFigures& f) {
  std::string row = fmt::format("{},{},{},{},{},{},{},{}", files::CsvField(axis), files::CsvField(value), f.episodes,
                                f.items, f.sorted, f.correct_sort_rate ? Number(*f.correct_sort_rate) : "",
                                Number(f.ci95.first), Number(f.ci95.second));
  for (const auto o : Failures()) row += fmt::format(",{}", f.outcomes.at(o));
  return row + fmt::format(",{}\n", f.episodes_failed);
}

// ---- summary.md ----

std::string Percent(const std::optional<double>& v) { return v ? fmt::format("{:.1f} %", 100 * *v) : "n/a"; }

// The pick cycle by phase, the phases that cost most first.
std::string MarkdownPhases(const GroupFigures& all) {
  if (all.cycle_phases_s.empty()) return "";
  std::vector<std::pair<std::string, double>> phases(all.cycle_phases_s.begin(), all.cycle_phases_s.end());
  std::stable_sort(phases.begin(), phases.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  const bool bounded = !all.cycle_phases_bound_s.empty();
  std::string md = std::string("Cycle by phase, mean simulated seconds per attempt") +
                   (bounded ? " (in brackets the arm's least time over the same paths):" : ":");
  for (const auto& [phase, seconds] : phases) {
    const auto bound = all.cycle_phases_bound_s.find(phase);
    md += fmt::format(" {} {:.2f}", phase, seconds) +
          (bound != all.cycle_phases_bound_s.end() ? fmt::format(" ({:.2f}),", bound->second) : ",");
  }
  md.back() = '.';
  md += fmt::format(" Torque-saturated control periods {}, largest tracking error {:.4f} rad.",
                    all.torque_saturated_samples, all.tracking_max_error_rad);
  if (all.carry_slip_mean_mm) {
    md += fmt::format(
        " Held objects slipped {:.2f} mm on average from grasp to bin (largest {:.1f} mm, largest turn"
        " {:.1f} deg).",
        *all.carry_slip_mean_mm, all.carry_slip_max_mm, all.carry_turn_max_deg);
  }
  return md + "\n\n";
}

std::string MarkdownOverview(const SweepSpec& spec, const GroupFigures& all) {
  std::string md =
      fmt::format("# Sweep {}\n\n{} episodes ({} failed to run) of {} in the spec, {} items.\n\n",
                  spec.source.filename().string(), all.episodes, all.episodes_failed, spec.EpisodeCount(), all.items);
  md +=
      "| items | correct-sort rate (95 % CI) | recognition accuracy | grasp success | mean cycle per item | "
      "the arm's least time (cycle / it) | picks per hour |\n"
      "|---|---|---|---|---|---|---|\n";
  md += fmt::format("| {} | {} ({:.1f}-{:.1f} %) | {} | {} | {} | {} | {} |\n\n", all.items,
                    Percent(all.correct_sort_rate), 100 * all.ci95.first, 100 * all.ci95.second,
                    Percent(all.recognition_accuracy), Percent(all.grasp_success_rate),
                    all.mean_cycle_time_s ? fmt::format("{:.1f} s", *all.mean_cycle_time_s) : "n/a",
                    all.mean_cycle_bound_s && all.cycle_to_bound
                        ? fmt::format("{:.1f} s (x{:.2f})", *all.mean_cycle_bound_s, *all.cycle_to_bound)
                        : "n/a",
                    all.picks_per_hour ? fmt::format("{:.0f}", *all.picks_per_hour) : "n/a");
  md += MarkdownPhases(all);
  if (all.unknown > 0 || all.known_rejected > 0) {
    md += fmt::format(
        "Unknown objects: {} of {} rejected ({}), {} sorted into a category bin ({}); known objects wrongly "
        "rejected: {} of {} ({}).\n\n",
        all.unknown_rejected, all.unknown, Percent(simcell::Ratio(all.unknown_rejected, all.unknown)),
        all.unknown_in_category_bin, Percent(simcell::Ratio(all.unknown_in_category_bin, all.unknown)),
        all.known_rejected, all.known, Percent(simcell::Ratio(all.known_rejected, all.known)));
  }
  md += "Outcomes: ";
  for (size_t i = 0; i < cell::kItemOutcomes.size(); ++i) {
    const auto o = cell::kItemOutcomes[i];
    md += fmt::format("{} {}{}", cell::ToString(o), all.outcomes.at(o),
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
    for (const auto o : Failures()) counts += (counts.empty() ? "" : " / ") + std::to_string(f.outcomes.at(o));
    md += fmt::format("| {} | {} | {} | {} | {:.1f}-{:.1f} % | {} |\n", g.label, f.episodes, f.items,
                      Percent(f.correct_sort_rate), 100 * f.ci95.first, 100 * f.ci95.second, counts);
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
    if (!f.correct_sort_rate) continue;
    std::string label = groups[i].label;
    std::replace(label.begin(), label.end(), '"', '\'');
    rows += fmt::format("{} \"{}\" {} {} {}\n", i, label, 100 * *f.correct_sort_rate, 100 * f.ci95.first,
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

namespace {

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

}  // namespace

// The episodes' hand-eye self-calibrations: how many succeeded, the camera error they left (median
// and largest) against the nominal pose's, and what they cost. Null when no episode calibrated.
// The upper median and the largest of values (not empty).
double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
double Largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

nlohmann::json CalibrationSummary(const std::vector<SweepRecord>& records) {
  std::vector<double> error_m, error_rad, prior_m, prior_rad, duration_s;
  int ok = 0;
  for (const auto& r : records) {
    if (!r.ok() || !r.summary.calibration) continue;
    const simcell::CalibrationFigures& c = *r.summary.calibration;
    ok += c.status == "ok";
    error_m.push_back(c.error_m), error_rad.push_back(c.error_rad);
    prior_m.push_back(c.prior_error_m), prior_rad.push_back(c.prior_error_rad);
    duration_s.push_back(c.duration_s);
  }
  if (error_m.empty()) return nullptr;
  return {{"episodes", error_m.size()},
          {"ok", ok},
          {"median_error_m", Median(error_m)},
          {"max_error_m", Largest(error_m)},
          {"median_error_rad", Median(error_rad)},
          {"max_error_rad", Largest(error_rad)},
          {"max_prior_error_m", Largest(prior_m)},
          {"max_prior_error_rad", Largest(prior_rad)},
          {"mean_duration_s", std::accumulate(duration_s.begin(), duration_s.end(), 0.0) / duration_s.size()}};
}

std::string MarkdownCalibration(const nlohmann::json& c) {
  if (c.is_null()) return "";
  return fmt::format(
      "\nSelf-calibration in {} episodes ({} ok): camera error median {:.2f} mm / {:.4f} rad, largest {:.2f} mm / "
      "{:.4f} rad (the nominal pose's largest: {:.1f} mm / {:.4f} rad); {:.1f} simulated s each.\n",
      c["episodes"].get<int>(), c["ok"].get<int>(), 1000 * c["median_error_m"].get<double>(),
      c["median_error_rad"].get<double>(), 1000 * c["max_error_m"].get<double>(), c["max_error_rad"].get<double>(),
      1000 * c["max_prior_error_m"].get<double>(), c["max_prior_error_rad"].get<double>(),
      c["mean_duration_s"].get<double>());
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

// The machine's figures: peak memory per worker and wall time per episode (median and largest).
nlohmann::json ResourcesSummary(const std::vector<SweepRecord>& records) {
  std::vector<double> memory_mb, wall_s;
  for (const auto& r : records) {
    if (r.peak_memory_mb) memory_mb.push_back(*r.peak_memory_mb);
    wall_s.push_back(r.wall_time_s);
  }
  nlohmann::json resources = nlohmann::json::object();
  if (!memory_mb.empty()) {
    resources["worker_peak_memory_mb"] = {{"median", Median(memory_mb)}, {"max", Largest(memory_mb)}};
  }
  if (!wall_s.empty()) {
    resources["episode_wall_time_s"] = {{"median", Median(wall_s)}, {"max", Largest(wall_s)}};
  }
  return resources;
}

std::string MarkdownRuns(const nlohmann::json& runs, const nlohmann::json& resources) {
  std::string md = fmt::format("Worker runs: ok {}, crashed {}, timeout {}", runs["ok"].get<int>(),
                               runs["crashed"].get<int>(), runs["timeout"].get<int>());
  for (const auto& f : runs["not_ok"]) {
    md += fmt::format("; episode {} {} ({})", f["episode"].get<int>(), f["status"].get<std::string>(),
                      f["error"].get<std::string>());
  }
  md += ".";
  if (resources.contains("worker_peak_memory_mb")) {
    const auto& m = resources["worker_peak_memory_mb"];
    md += fmt::format(" Peak memory per worker: median {:.0f} MiB, largest {:.0f} MiB.", m["median"].get<double>(),
                      m["max"].get<double>());
  }
  return md + "\n\n";
}

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
  summary["spec"] = spec.source.string();
  summary["episodes_in_spec"] = spec.EpisodeCount();
  nlohmann::json by_axis = nlohmann::json::object();
  std::string csv = CsvHeader() + CsvRow("all", "all", all);
  std::string md = MarkdownOverview(spec, all);
  summary["runs"] = RunsSummary(records);
  summary["resources"] = ResourcesSummary(records);
  md += MarkdownRuns(summary["runs"], summary["resources"]);
  summary["calibration"] = CalibrationSummary(records);
  md += MarkdownCalibration(summary["calibration"]);
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
      by_axis[axis.name][g.label] = FiguresJson(g.figures);
      csv += CsvRow(axis.name, g.label, g.figures);
    }
    md += MarkdownAxisTable(axis.name, groups);
    Plot(dir, axis.name, groups);
    md += "\n![correct-sort rate by " + axis.name + "](plot_" + axis.name + ".png)\n";
  }
  summary["by_axis"] = by_axis;
  nlohmann::json by_object = nlohmann::json::object();
  const std::vector<AxisGroup> objects = GroupByObject(records);
  for (const auto& g : objects) {
    by_object[g.label] = FiguresJson(g.figures);
    csv += CsvRow("object", g.label, g.figures);
  }
  if (!objects.empty()) md += MarkdownAxisTable("object", objects);
  summary["by_object"] = by_object;
  files::WriteTextFile(dir / "summary.csv", csv);
  files::WriteTextFile(dir / "summary.md", md);
  files::WriteJson(dir / "summary.json", summary);
  return summary;
}

}  // namespace sortcell::app
