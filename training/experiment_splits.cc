#include "training/experiment_splits.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/seeding.h"

namespace sortcell::training {

Trial FrameSplit(const Dataset& d) {
  Trial s;
  for (size_t i = 0; i < d.samples.size(); ++i) {
    (d.samples[i].frame % 4 == 3 ? s.test : s.train).push_back(static_cast<int>(i));
  }
  s.description = {{"test", "every fourth view (frame % 4 == 3) of every turntable sequence"}};
  return s;
}

namespace {

// Each category's instances in the seeded order they are held out in.
std::map<std::string, std::vector<std::string>> HoldOutOrder(const Dataset& d, uint64_t seed) {
  std::map<std::string, std::set<std::string>> instances;
  for (const auto& sample : d.samples) instances[sample.category].insert(sample.instance);
  std::mt19937_64 rng = EpisodeRng(seed, 0x5911);
  std::map<std::string, std::vector<std::string>> order;
  for (const auto& [category, names] : instances) {
    if (names.size() < 2) {
      throw std::invalid_argument("unseen-instance split: category '" + category +
                                  "' has one instance (each needs one to train and one to test)");
    }
    std::vector<std::string> v(names.begin(), names.end());
    std::shuffle(v.begin(), v.end(), rng);
    order[category] = std::move(v);
  }
  return order;
}

}  // namespace

std::vector<Trial> LeaveOneInstanceOutTrials(const Dataset& d, int trials, uint64_t seed) {
  if (trials < 0)
    throw std::invalid_argument("unseen-instance split: trials must be >= 0, got " + std::to_string(trials));
  const auto order = HoldOutOrder(d, seed);
  if (trials == 0) {
    for (const auto& [category, names] : order) trials = std::max(trials, static_cast<int>(names.size()));
  }
  std::vector<Trial> out(trials);
  for (int t = 0; t < trials; ++t) {
    std::set<std::string> held_out;
    nlohmann::json test_instances = nlohmann::json::object();
    for (const auto& [category, names] : order) {
      const std::string& pick = names[t % names.size()];
      held_out.insert(pick);
      test_instances[category] = pick;
    }
    Trial& s = out[t];
    for (size_t i = 0; i < d.samples.size(); ++i) {
      (held_out.count(d.samples[i].instance) ? s.test : s.train).push_back(static_cast<int>(i));
    }
    s.request.group_by = Grouping::kInstance;
    s.description = {{"test_instances", test_instances}};
  }
  return out;
}

Trial SequenceSplit(const Dataset& d, uint64_t seed) {
  // Sequences: (instance, elevation, third of the revolution); nine per instance.
  const bool has_paper_categories = std::any_of(d.samples.begin(), d.samples.end(), [](const Sample& s) {
    return s.category == "apple" || s.category == "orange";
  });
  const auto used = [&](const Sample& s) {
    return !has_paper_categories || s.category == "apple" || s.category == "orange";
  };
  std::map<std::string, std::set<std::pair<double, int>>> sequences;
  const auto part = [&](const Sample& s) { return 3 * s.frame / std::max(1, d.views); };
  for (const auto& s : d.samples) {
    if (used(s)) sequences[s.instance].insert({s.elevation_deg, part(s)});
  }
  std::mt19937_64 rng = EpisodeRng(seed, 0x5e9);
  std::map<std::string, std::set<std::pair<double, int>>> test;
  nlohmann::json chosen = nlohmann::json::object();
  for (const auto& [instance, seqs] : sequences) {
    std::vector<std::pair<double, int>> v(seqs.begin(), seqs.end());
    std::shuffle(v.begin(), v.end(), rng);
    for (size_t k = 0; k < std::min<size_t>(2, v.size()); ++k) {
      test[instance].insert(v[k]);
      chosen[instance].push_back({{"elevation_deg", v[k].first}, {"part", v[k].second}});
    }
  }
  Trial s;
  for (size_t i = 0; i < d.samples.size(); ++i) {
    const Sample& x = d.samples[i];
    if (!sequences.count(x.instance)) continue;
    (test[x.instance].count({x.elevation_deg, part(x)}) ? s.test : s.train).push_back(static_cast<int>(i));
  }
  s.request.label_kind = perception::LabelKind::kInstance;
  s.description = {{"test_sequences", chosen}, {"sequences_per_instance", 9}};
  return s;
}

}  // namespace sortcell::training
