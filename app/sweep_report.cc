#include "app/sweep_report.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "app/episode_scoring.h"
#include "app/output_dir.h"

namespace sortcell::app {
namespace {

// Totals over a group of episodes.
struct Tally {
  int episodes = 0, failed_episodes = 0, attempts = 0, grasps = 0;
  double sim_s = 0, wall_s = 0;
  ItemTally items;

  void Add(const nlohmann::json& record) {
    ++episodes;
    if (record.value("status", "") != "ok") {
      ++failed_episodes;
      return;
    }
    const nlohmann::json& s = record["summary"];
    attempts += s.value("grasp_attempts", 0);
    grasps += s.value("grasps", 0);
    sim_s += s.value("sim_time_s", 0.0);
    wall_s += s.value("wall_time_s", 0.0);
    for (const auto& item : record["items"]) items.Add(item);
  }

  nlohmann::json Json() const {
    const auto ratio = [](double a, double b) { return b > 0 ? nlohmann::json(a / b) : nlohmann::json(nullptr); };
    const int sorted = items.Count("sorted");
    const auto [low, high] = WilsonInterval(sorted, items.items);
    return {{"episodes", episodes},
            {"episodes_failed", failed_episodes},
            {"items", items.items},
            {"correct_sort_rate", ratio(sorted, items.items)},
            {"correct_sort_rate_ci95", {low, high}},
            {"outcomes", items.OutcomeCounts()},
            {"recognition_accuracy", ratio(items.recognised, items.classified)},
            {"grasp_success_rate", ratio(grasps, attempts)},
            {"grasp_attempts", attempts},
            {"mean_cycle_time_s", ratio(items.cycle_s, items.completed)},
            {"sim_time_s", sim_s},
            {"episode_wall_time_s", wall_s},
            {"real_time_factor", ratio(sim_s, wall_s)}};
  }
};

std::string Percent(const nlohmann::json& v) {
  if (v.is_null()) return "n/a";
  char text[16];
  std::snprintf(text, sizeof text, "%.1f %%", 100 * v.get<double>());
  return text;
}

// The label of an axis value: a range axis is cut into 4 equal bins, a model shows its file name.
std::string ValueLabel(const SweepAxis& axis, const nlohmann::json& value) {
  char text[64];
  if (axis.name == "model") return std::filesystem::path(value.get<std::string>()).filename().string();
  if (axis.is_range() && axis.name != "objects" && axis.max > axis.min) {
    const double width = (axis.max - axis.min) / 4;
    const int bin = std::min(3, static_cast<int>((value.get<double>() - axis.min) / width));
    std::snprintf(text, sizeof text, "%.3g-%.3g", axis.min + bin * width, axis.min + (bin + 1) * width);
    return text;
  }
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  std::snprintf(text, sizeof text, "%.4g", value.get<double>());
  return text;
}

void Plot(const std::filesystem::path& dir, const std::string& axis,
          const std::vector<std::pair<std::string, nlohmann::json>>& rows) {
  const std::filesystem::path data = dir / ("plot_" + axis + ".dat");
  {
    std::ofstream out(data);
    for (size_t i = 0; i < rows.size(); ++i) {
      const auto& j = rows[i].second;
      if (j["correct_sort_rate"].is_null()) continue;
      out << i << " \"" << rows[i].first << "\" " << 100 * j["correct_sort_rate"].get<double>() << " "
          << 100 * j["correct_sort_rate_ci95"][0].get<double>() << " " << 100 * j["correct_sort_rate_ci95"][1].get<double>()
          << "\n";
    }
  }
  const std::filesystem::path png = dir / ("plot_" + axis + ".png");
  FILE* gnuplot = popen("gnuplot 2>/dev/null", "w");
  if (gnuplot == nullptr) return;
  std::fprintf(gnuplot,
               "set terminal pngcairo size 800,500\nset output '%s'\nset title 'Correct-sort rate by %s (95%% CI)'\n"
               "set ylabel 'items in the correct bin (%%)'\nset xlabel '%s'\nset yrange [0:105]\nset grid ytics\n"
               "set xrange [-0.5:%.1f]\nset key off\n"
               "plot '%s' using 1:3:4:5:xticlabels(2) with yerrorbars pt 7 ps 1.5 lw 2\n",
               png.string().c_str(), axis.c_str(), axis.c_str(), rows.size() - 0.5, data.string().c_str());
  if (pclose(gnuplot) != 0) spdlog::warn("gnuplot could not draw {} (is gnuplot installed?)", png.string());
  std::filesystem::remove(data);
}

}  // namespace

std::pair<double, double> WilsonInterval(int successes, int n) {
  if (n <= 0) return {0.0, 1.0};
  const double z = 1.959963984540054, p = static_cast<double>(successes) / n;
  const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / (1 + z * z / n);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

nlohmann::json WriteSweepReport(const std::filesystem::path& dir, const SweepSpec& spec,
                                const std::vector<nlohmann::json>& records) {
  Tally all;
  for (const auto& r : records) all.Add(r);
  nlohmann::json summary = all.Json();
  summary["spec"] = spec.source.string();
  summary["episodes_in_spec"] = spec.EpisodeCount();
  nlohmann::json by_axis = nlohmann::json::object();

  std::ofstream csv(dir / "summary.csv");
  csv << "axis,value,episodes,items,sorted,correct_sort_rate,ci95_low,ci95_high";
  for (const auto& o : kOutcomes) {
    if (o != "sorted") csv << "," << o;
  }
  csv << ",episodes_failed\n";
  const auto csv_row = [&](const std::string& axis, const std::string& value, const nlohmann::json& j) {
    csv << axis << ",\"" << value << "\"," << j["episodes"] << "," << j["items"] << "," << j["outcomes"]["sorted"] << ","
        << (j["correct_sort_rate"].is_null() ? "" : j["correct_sort_rate"].dump()) << "," << j["correct_sort_rate_ci95"][0]
        << "," << j["correct_sort_rate_ci95"][1];
    for (const auto& o : kOutcomes) {
      if (o != "sorted") csv << "," << j["outcomes"][o];
    }
    csv << "," << j["episodes_failed"] << "\n";
  };
  csv_row("all", "all", summary);

  std::string md = "# Sweep " + spec.source.filename().string() + "\n\n";
  md += std::to_string(all.episodes) + " episodes (" + std::to_string(all.failed_episodes) + " failed to run) of " +
        std::to_string(spec.EpisodeCount()) + " in the spec, " + std::to_string(all.items.items) + " items.\n\n";
  md += "| items | correct-sort rate (95 % CI) | recognition accuracy | grasp success | mean cycle per item |\n|---|---|---|---|---|\n";
  char line[512], cycle[32] = "n/a";
  if (!summary["mean_cycle_time_s"].is_null()) std::snprintf(cycle, sizeof cycle, "%.1f s", summary["mean_cycle_time_s"].get<double>());
  std::snprintf(line, sizeof line, "| %d | %s (%.1f-%.1f %%) | %s | %s | %s |\n\n", all.items.items,
                Percent(summary["correct_sort_rate"]).c_str(), 100 * summary["correct_sort_rate_ci95"][0].get<double>(),
                100 * summary["correct_sort_rate_ci95"][1].get<double>(), Percent(summary["recognition_accuracy"]).c_str(),
                Percent(summary["grasp_success_rate"]).c_str(), cycle);
  md += line;
  md += "Outcomes: ";
  for (const auto& o : kOutcomes) md += o + " " + std::to_string(summary["outcomes"][o].get<int>()) + (o == kOutcomes.back() ? ".\n" : ", ");

  for (const auto& axis : spec.axes) {
    std::map<std::string, Tally> groups;
    std::vector<std::string> order;
    for (const auto& r : records) {
      if (!r.contains("axes") || !r["axes"].contains(axis.name)) continue;
      const std::string label = ValueLabel(axis, r["axes"][axis.name]);
      if (!groups.count(label)) order.push_back(label);
      groups[label].Add(r);
    }
    if (groups.size() < 2) continue;
    std::sort(order.begin(), order.end(), [&](const std::string& a, const std::string& b) {
      try {
        return std::stod(a) < std::stod(b);
      } catch (const std::logic_error&) {
        return a < b;
      }
    });
    md += "\n## By " + axis.name + "\n\n| " + axis.name +
          " | episodes | items | correct-sort rate | 95 % CI | failures (wrong bin / dropped / grasp failed / unreachable / not detected / left) |\n|---|---|---|---|---|---|\n";
    std::vector<std::pair<std::string, nlohmann::json>> rows;
    for (const auto& label : order) {
      const nlohmann::json j = groups[label].Json();
      by_axis[axis.name][label] = j;
      csv_row(axis.name, label, j);
      rows.emplace_back(label, j);
      const auto& o = j["outcomes"];
      std::snprintf(line, sizeof line, "| %s | %d | %d | %s | %.1f-%.1f %% | %d / %d / %d / %d / %d / %d |\n", label.c_str(),
                    j["episodes"].get<int>(), j["items"].get<int>(), Percent(j["correct_sort_rate"]).c_str(),
                    100 * j["correct_sort_rate_ci95"][0].get<double>(), 100 * j["correct_sort_rate_ci95"][1].get<double>(),
                    o["wrong_bin"].get<int>(), o["dropped"].get<int>(), o["grasp_failed"].get<int>(),
                    o["unreachable"].get<int>(), o["not_detected"].get<int>(), o["left_on_table"].get<int>());
      md += line;
    }
    Plot(dir, axis.name, rows);
    md += "\n![correct-sort rate by " + axis.name + "](plot_" + axis.name + ".png)\n";
  }
  summary["by_axis"] = by_axis;
  std::ofstream(dir / "summary.md") << md;
  WriteJson(dir / "summary.json", summary);
  return summary;
}

}  // namespace sortcell::app
