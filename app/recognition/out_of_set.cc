#include "app/recognition/out_of_set.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <numeric>

namespace sortcell::app {
namespace {

constexpr double kThresholds[] = {0.5, 0.6, 0.7, 0.8, 0.9};

double Quantile(const std::vector<double>& sorted, double q) {
  return sorted.empty() ? 0.0 : sorted[static_cast<size_t>(q * (sorted.size() - 1) + 0.5)];
}

double RejectedShare(const std::vector<double>& confidences, double threshold) {
  const auto below = std::count_if(confidences.begin(), confidences.end(), [threshold](double c) { return c < threshold; });
  return confidences.empty() ? 0.0 : static_cast<double>(below) / confidences.size();
}

}  // namespace

void SplitBySet(const perception::RecognitionModel& model, const Dataset& dataset, std::vector<int>& in_set,
                std::vector<int>& out_of_set) {
  in_set.clear();
  out_of_set.clear();
  for (size_t r = 0; r < dataset.samples.size(); ++r) {
    const std::string& label = Dataset::Label(dataset.samples[r], model.label_kind);
    const bool known = std::find(model.classes.begin(), model.classes.end(), label) != model.classes.end();
    (known ? in_set : out_of_set).push_back(static_cast<int>(r));
  }
}

OutOfSetReport ClassifyOutOfSet(const perception::RecognitionModel& model, const Dataset& dataset,
                                const std::vector<int>& rows) {
  OutOfSetReport report;
  for (int r : rows) {
    const Sample& s = dataset.samples.at(r);
    const auto result = model.Classify(s.parts);
    OutOfSetCategory& c = report[Dataset::Label(s, model.label_kind)];
    ++c.samples;
    ++c.called[result.name];
    c.confidences.push_back(result.confidence);
  }
  for (auto& [name, c] : report) std::sort(c.confidences.begin(), c.confidences.end());
  return report;
}

nlohmann::json OutOfSetJson(const OutOfSetReport& report) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, c] : report) {
    const double mean = c.confidences.empty() ? 0.0
                                              : std::accumulate(c.confidences.begin(), c.confidences.end(), 0.0) /
                                                    c.confidences.size();
    nlohmann::json rejected;
    for (double t : kThresholds) rejected[fmt::format("{:.1f}", t)] = RejectedShare(c.confidences, t);
    out[name] = {{"samples", c.samples},
                 {"called", c.called},
                 {"confidence",
                  {{"mean", mean},
                   {"median", Quantile(c.confidences, 0.5)},
                   {"p10", Quantile(c.confidences, 0.1)},
                   {"p90", Quantile(c.confidences, 0.9)},
                   {"max", c.confidences.empty() ? 0.0 : c.confidences.back()}}},
                 {"rejected_below", rejected}};
  }
  return out;
}

std::string OutOfSetMarkdown(const OutOfSetReport& report) {
  std::string md = "## Samples of categories the model does not know\n\n"
                   "| category | samples | called | confidence mean / median / p90 / max |";
  for (double t : kThresholds) md += fmt::format(" rejected below {:.1f} |", t);
  md += "\n|---|---:|---|---:|";
  for (size_t i = 0; i < std::size(kThresholds); ++i) md += "---:|";
  md += "\n";
  for (const auto& [name, c] : report) {
    std::string called;
    for (const auto& [cls, n] : c.called) called += fmt::format("{}{} {}", called.empty() ? "" : ", ", cls, n);
    const double mean = std::accumulate(c.confidences.begin(), c.confidences.end(), 0.0) / std::max<size_t>(1, c.confidences.size());
    md += fmt::format("| {} | {} | {} | {:.2f} / {:.2f} / {:.2f} / {:.2f} |", name, c.samples, called, mean,
                      Quantile(c.confidences, 0.5), Quantile(c.confidences, 0.9),
                      c.confidences.empty() ? 0.0 : c.confidences.back());
    for (double t : kThresholds) md += fmt::format(" {:.0f} % |", 100 * RejectedShare(c.confidences, t));
    md += "\n";
  }
  return md;
}

}  // namespace sortcell::app
