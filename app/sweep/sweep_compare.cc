#include "app/sweep/sweep_compare.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "files/output_dir.h"
#include "app/sweep/sweep_report.h"

namespace sortcell::app {
namespace {

SortRate RateOf(const std::vector<SweepRecord>& records) {
  simcell::ItemTally tally;  // Counted as the sweep's summary counts them.
  for (const auto& record : records) {
    if (!record.ok()) continue;
    for (const auto& item : record.items) tally.Add(item);
  }
  SortRate r;
  r.items = tally.items;
  r.sorted = tally.Count(cell::ItemOutcome::kSorted);
  if (r.items > 0) r.rate = static_cast<double>(r.sorted) / r.items;
  std::tie(r.low, r.high) = WilsonInterval(r.sorted, r.items);
  return r;
}

std::map<int, const SweepRecord*> ByEpisode(const std::vector<SweepRecord>& records) {
  std::map<int, const SweepRecord*> by;
  for (const auto& r : records) by[r.episode] = &r;
  return by;
}

void CheckSameEpisode(const SweepRecord& a, const SweepRecord& b) {
  if (a.seed != b.seed) {
    throw std::invalid_argument(
        fmt::format("episode {}: seed {} in A, {} in B: not the same episodes", a.episode, a.seed, b.seed));
  }
  // The noise's draw (axis noise_seed) is the one axis that leaves the scene as it is: two draws compared
  // show the spread between realisations of the sensor.
  nlohmann::json scene_a = a.axes, scene_b = b.axes;
  scene_a.erase("noise_seed");
  scene_b.erase("noise_seed");
  if (scene_a != scene_b) {
    throw std::invalid_argument(fmt::format("episode {}: axes {} in A, {} in B: not the same episodes", a.episode,
                                            a.axes.dump(), b.axes.dump()));
  }
}

// Pairs the items of two runs of one episode by name.
void PairItems(const SweepRecord& a, const SweepRecord& b, SweepComparison& c) {
  std::map<std::string, cell::ItemOutcome> in_b;
  for (const auto& item : b.items) in_b[item.name] = item.outcome;
  for (const auto& item : a.items) {
    const auto it = in_b.find(item.name);
    if (it == in_b.end()) {
      ++c.items_unpaired;
      continue;
    }
    ++c.items_paired;
    const bool sorted_a = item.outcome == cell::ItemOutcome::kSorted;
    const bool sorted_b = it->second == cell::ItemOutcome::kSorted;
    c.sorted_only_in_a += sorted_a && !sorted_b;
    c.sorted_only_in_b += sorted_b && !sorted_a;
    if (item.outcome != it->second)
      c.changed.push_back({a.episode, a.seed, a.axes, item.name, item.outcome, it->second});
    in_b.erase(it);
  }
  c.items_unpaired += static_cast<int>(in_b.size());
}

std::string Verdict(const SweepComparison& c) {
  if (c.sorted_only_in_a + c.sorted_only_in_b == 0) return "no difference";
  if (c.sorted_only_in_a == c.sorted_only_in_b) return "as many items changed each way: no difference in rate";
  const char* better = c.sorted_only_in_b > c.sorted_only_in_a ? "B" : "A";
  return c.significant ? fmt::format("{} sorts more, significant at 5 %", better)
                       : fmt::format("{} sorts more, not significant at 5 %", better);
}

std::string HtmlEscaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

// A link to what sweep `dir` kept of one item: its failure (or its episode's row) on the sweep's report
// page, else the episode's metrics.json; the plain label when the sweep kept neither.
std::string ItemLink(const std::filesystem::path& dir, const ItemChange& change, cell::ItemOutcome outcome,
                     const std::filesystem::path& page_dir) {
  const std::string label = cell::ToString(outcome);
  std::error_code ec;
  std::filesystem::path target;
  std::string anchor;
  if (std::filesystem::is_regular_file(dir / "report/index.html", ec)) {
    target = dir / "report/index.html";
    anchor = outcome == cell::ItemOutcome::kSorted ? fmt::format("#episode-{}", change.episode)
                                                   : fmt::format("#failure-{}-{}", change.episode, change.item);
  } else if (std::filesystem::is_directory(dir / fmt::format("episodes/{:06d}", change.episode), ec)) {
    target = dir / fmt::format("episodes/{:06d}/metrics.json", change.episode);
  } else {
    return HtmlEscaped(label) + " (not kept)";
  }
  const std::filesystem::path relative = std::filesystem::relative(target, page_dir, ec);
  return fmt::format("<a href=\"{}{}\">{}</a>", HtmlEscaped((ec ? target : relative).generic_string()),
                     HtmlEscaped(anchor), HtmlEscaped(label));
}

std::string RateText(const SortRate& r) {
  return fmt::format("{:.1f} % ({:.1f}-{:.1f} %), {} of {} items", 100 * r.rate, 100 * r.low, 100 * r.high, r.sorted,
                     r.items);
}

}  // namespace

double ExactMcNemarP(int b, int c) {
  const int n = b + c, k = std::min(b, c);
  if (n == 0) return 1.0;
  // Summed in logs: n reaches thousands in a large sweep, where the binomial terms underflow alone.
  double tail = 0;
  for (int i = 0; i <= k; ++i) {
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) - n * std::log(2.0));
  }
  return std::min(1.0, 2 * tail);
}

SweepComparison CompareSweepRecords(const std::vector<SweepRecord>& a, const std::vector<SweepRecord>& b) {
  SweepComparison c;
  c.a = RateOf(a);
  c.b = RateOf(b);
  const auto in_a = ByEpisode(a), in_b = ByEpisode(b);
  for (const auto& [episode, ra] : in_a) {
    const auto it = in_b.find(episode);
    if (it == in_b.end()) {
      c.episodes_unpaired.push_back(episode);
      continue;
    }
    CheckSameEpisode(*ra, *it->second);
    if (!ra->ok() || !it->second->ok()) {
      c.episodes_unpaired.push_back(episode);
      continue;
    }
    ++c.episodes_paired;
    PairItems(*ra, *it->second, c);
  }
  for (const auto& [episode, rb] : in_b) {
    if (!in_a.count(episode)) c.episodes_unpaired.push_back(episode);
  }
  std::sort(c.episodes_unpaired.begin(), c.episodes_unpaired.end());
  std::sort(c.changed.begin(), c.changed.end(), [](const ItemChange& x, const ItemChange& y) {
    return std::tie(x.episode, x.item) < std::tie(y.episode, y.item);
  });
  c.p_value = ExactMcNemarP(c.sorted_only_in_a, c.sorted_only_in_b);
  c.significant = c.p_value < 0.05;
  return c;
}

SweepComparison CompareSweepFolders(const std::filesystem::path& a, const std::filesystem::path& b) {
  const std::vector<SweepRecord> records[2] = {ReadSweepFolder(a), ReadSweepFolder(b)};
  SweepComparison c = CompareSweepRecords(records[0], records[1]);
  std::error_code ec;
  if (std::filesystem::exists(a / "spec.yaml", ec) && std::filesystem::exists(b / "spec.yaml", ec)) {
    c.specs_differ = files::ReadTextFile(a / "spec.yaml") != files::ReadTextFile(b / "spec.yaml");
  }
  return c;
}

std::string ComparisonText(const SweepComparison& c, const std::filesystem::path& a, const std::filesystem::path& b) {
  std::string text = fmt::format("A {}: {}\nB {}: {}\n", a.string(), RateText(c.a), b.string(), RateText(c.b));
  text +=
      fmt::format("Paired: {} items in {} episodes; sorted in A only {}, in B only {}; exact McNemar p = {:.3g}: {}.\n",
                  c.items_paired, c.episodes_paired, c.sorted_only_in_a, c.sorted_only_in_b, c.p_value, Verdict(c));
  if (!c.episodes_unpaired.empty() || c.items_unpaired > 0) {
    text += fmt::format("Not paired: {} episodes (in one sweep only, or crashed or timed out), {} items.\n",
                        c.episodes_unpaired.size(), c.items_unpaired);
  }
  if (c.specs_differ)
    text += "The folders' spec.yaml differ (overrides or an edited spec); episodes checked one by one.\n";
  text += fmt::format("Items that changed outcome: {}\n", c.changed.size());
  for (const auto& ch : c.changed) {
    text += fmt::format("  episode {} (seed {}{}{}): {}: {} -> {}\n", ch.episode, ch.seed, ch.axes.empty() ? "" : ", ",
                        AxesText(ch.axes), ch.item, cell::ToString(ch.before), cell::ToString(ch.after));
  }
  return text;
}

nlohmann::json ComparisonJson(const SweepComparison& c, const std::filesystem::path& a,
                              const std::filesystem::path& b) {
  const auto rate = [](const SortRate& r) {
    return nlohmann::json{{"sorted", r.sorted}, {"items", r.items}, {"rate", r.rate}, {"ci95", {r.low, r.high}}};
  };
  nlohmann::json changed = nlohmann::json::array();
  for (const auto& ch : c.changed) {
    changed.push_back({{"episode", ch.episode},
                       {"seed", ch.seed},
                       {"axes", ch.axes},
                       {"item", ch.item},
                       {"before", cell::ToString(ch.before)},
                       {"after", cell::ToString(ch.after)}});
  }
  return {{"a", {{"dir", a.string()}, {"correct_sort", rate(c.a)}}},
          {"b", {{"dir", b.string()}, {"correct_sort", rate(c.b)}}},
          {"episodes_paired", c.episodes_paired},
          {"episodes_unpaired", c.episodes_unpaired},
          {"items_paired", c.items_paired},
          {"items_unpaired", c.items_unpaired},
          {"sorted_only_in_a", c.sorted_only_in_a},
          {"sorted_only_in_b", c.sorted_only_in_b},
          {"mcnemar_exact_p", c.p_value},
          {"significant_at_5_percent", c.significant},
          {"specs_differ", c.specs_differ},
          {"changed", changed}};
}

std::string ComparisonHtml(const SweepComparison& c, const std::filesystem::path& a, const std::filesystem::path& b,
                           const std::filesystem::path& page_dir) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>SortCell: sweeps compared</title>\n"
      "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
      "padding:4px 8px;text-align:left}.better{color:#070}.worse{color:#a00}</style></head><body>\n"
      "<h1>Sweeps compared</h1>\n<table><tr><th></th><th>folder</th><th>correct-sort rate (95 % CI)</th></tr>\n";
  html += fmt::format("<tr><td>A</td><td>{}</td><td>{}</td></tr>\n", HtmlEscaped(a.string()), RateText(c.a));
  html += fmt::format("<tr><td>B</td><td>{}</td><td>{}</td></tr></table>\n", HtmlEscaped(b.string()), RateText(c.b));
  html += fmt::format(
      "<p>Paired: {} items in {} episodes; sorted in A only {}, in B only {}; exact McNemar p = {:.3g}: "
      "<b>{}</b>.</p>\n",
      c.items_paired, c.episodes_paired, c.sorted_only_in_a, c.sorted_only_in_b, c.p_value, Verdict(c));
  if (!c.episodes_unpaired.empty() || c.items_unpaired > 0) {
    html += fmt::format("<p>Not paired: {} episodes (in one sweep only, or crashed or timed out), {} items.</p>\n",
                        c.episodes_unpaired.size(), c.items_unpaired);
  }
  if (c.specs_differ)
    html += "<p>The folders' spec.yaml differ (overrides or an edited spec); episodes checked one by one.</p>\n";
  html += fmt::format("<h2>Items that changed outcome ({})</h2>\n", c.changed.size());
  html += "<table><tr><th>episode</th><th>seed</th><th>axes</th><th>item</th><th>A</th><th>B</th></tr>\n";
  for (const auto& ch : c.changed) {
    const bool better = ch.after == cell::ItemOutcome::kSorted, worse = ch.before == cell::ItemOutcome::kSorted;
    html +=
        fmt::format("<tr class=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                    better ? "better" : (worse ? "worse" : ""), ch.episode, ch.seed, HtmlEscaped(AxesText(ch.axes)),
                    HtmlEscaped(ch.item), ItemLink(a, ch, ch.before, page_dir), ItemLink(b, ch, ch.after, page_dir));
  }
  html += "</table>\n</body></html>\n";
  return html;
}

}  // namespace sortcell::app
