#include "training/out_of_set.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <numeric>

namespace sortcell::training {
namespace {

// The calibrated confidence is about uniform for views like the training ones (RecognitionModel::Result),
// so the useful thresholds are small ones: 0.05 rejects about 5 % of those (scenes/cells/default_reject.yaml).
constexpr double kThresholds[] = {0.01, 0.02, 0.05, 0.1, 0.2, 0.5};

double Quantile(const std::vector<double>& sorted, double q) {
  return sorted.empty() ? 0.0 : sorted[static_cast<size_t>(q * (sorted.size() - 1) + 0.5)];
}

double RejectedShare(const std::vector<double>& confidences, double threshold) {
  const auto below =
      std::count_if(confidences.begin(), confidences.end(), [threshold](double c) { return c < threshold; });
  return confidences.empty() ? 0.0 : static_cast<double>(below) / confidences.size();
}

double Mean(const std::vector<double>& values) {
  return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

nlohmann::json ConfidenceJson(const std::vector<double>& sorted) {
  return {{"mean", Mean(sorted)},
          {"median", Quantile(sorted, 0.5)},
          {"p10", Quantile(sorted, 0.1)},
          {"p90", Quantile(sorted, 0.9)},
          {"max", sorted.empty() ? 0.0 : sorted.back()}};
}

nlohmann::json RejectedJson(const std::vector<double>& confidences) {
  nlohmann::json rejected;
  for (double t : kThresholds) rejected[fmt::format("{:g}", t)] = RejectedShare(confidences, t);
  return rejected;
}

std::string CalledText(const std::map<std::string, int>& called) {
  std::string text;
  for (const auto& [cls, n] : called) text += fmt::format("{}{} {}", text.empty() ? "" : ", ", cls, n);
  return text;
}

// A Markdown table's head: `columns` and `rule` followed by a column per threshold.
std::string TableHead(const std::string& columns, const std::string& rule) {
  std::string head = columns, line = rule;
  for (double t : kThresholds) {
    head += fmt::format(" rejected below {:g} |", t);
    line += "---:|";
  }
  return head + "\n" + line + "\n";
}

// Counts over ten bins of 0.1 (a confidence of 1 in the last).
std::vector<int> Histogram(const std::vector<double>& confidences) {
  std::vector<int> bins(10, 0);
  for (double c : confidences) ++bins[std::clamp(static_cast<int>(c * 10), 0, 9)];
  return bins;
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
    out[name] = {{"samples", c.samples},
                 {"called", c.called},
                 {"confidence", ConfidenceJson(c.confidences)},
                 {"rejected_below", RejectedJson(c.confidences)}};
  }
  return out;
}

std::string OutOfSetMarkdown(const OutOfSetReport& report) {
  std::string md =
      "## Samples of categories the model does not know\n\n" +
      TableHead("| category | samples | called | confidence mean / median / p90 / max |", "|---|---:|---|---:|");
  for (const auto& [name, c] : report) {
    const std::string called = CalledText(c.called);
    md += fmt::format("| {} | {} | {} | {:.2f} / {:.2f} / {:.2f} / {:.2f} |", name, c.samples, called,
                      Mean(c.confidences), Quantile(c.confidences, 0.5), Quantile(c.confidences, 0.9),
                      c.confidences.empty() ? 0.0 : c.confidences.back());
    for (double t : kThresholds) md += fmt::format(" {:.0f} % |", 100 * RejectedShare(c.confidences, t));
    md += "\n";
  }
  return md;
}

std::map<std::string, InstanceResults> ClassifyByInstance(const perception::RecognitionModel& model,
                                                          const Dataset& dataset) {
  std::map<std::string, InstanceResults> report;
  for (const Sample& s : dataset.samples) {
    const std::string& truth = Dataset::Label(s, model.label_kind);
    const auto result = model.Classify(s.parts);
    InstanceResults& r = report[s.instance];
    r.category = truth;
    r.known = std::find(model.classes.begin(), model.classes.end(), truth) != model.classes.end();
    ++r.samples;
    r.correct += result.name == truth ? 1 : 0;
    ++r.called[result.name];
    r.confidences.push_back(result.confidence);
  }
  for (auto& [name, r] : report) std::sort(r.confidences.begin(), r.confidences.end());
  return report;
}

nlohmann::json InstanceJson(const std::map<std::string, InstanceResults>& report) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, r] : report) {
    out[name] = {
        {"category", r.category},
        {"known", r.known},
        {"samples", r.samples},
        {"correct_share", r.known ? nlohmann::json(static_cast<double>(r.correct) / r.samples) : nlohmann::json()},
        {"called", r.called},
        {"confidence", ConfidenceJson(r.confidences)},
        {"histogram", Histogram(r.confidences)},
        {"rejected_below", RejectedJson(r.confidences)}};
  }
  return out;
}

std::string InstanceMarkdown(const std::map<std::string, InstanceResults>& report) {
  std::string md =
      "## By instance\n\nKnown instances: the share called their category, and the share each threshold would "
      "reject wrongly; unknown ones (a category the model has no class for): the share it would rightly reject. "
      "Confidence histogram: samples per tenth, 0-0.1 first.\n\n" +
      TableHead("| instance | category | samples | called right | called | confidence median | histogram |",
                "|---|---|---:|---:|---|---:|---|");
  for (const auto& [name, r] : report) {
    const std::vector<int> bins = Histogram(r.confidences);
    std::string histogram;
    for (int n : bins) histogram += fmt::format("{}{}", histogram.empty() ? "" : " ", n);
    md += fmt::format("| {} | {}{} | {} | {} | {} | {:.2f} | {} |", name, r.category, r.known ? "" : " (unknown)",
                      r.samples, r.known ? fmt::format("{:.1f} %", 100.0 * r.correct / r.samples) : "-",
                      CalledText(r.called), Quantile(r.confidences, 0.5), histogram);
    for (double t : kThresholds) md += fmt::format(" {:.0f} % |", 100 * RejectedShare(r.confidences, t));
    md += "\n";
  }
  return md;
}

}  // namespace sortcell::training
