#include "cell/sorting_rules.h"

#include <set>

namespace sortcell::cell {

std::optional<std::string> SortingRules::BinOf(const std::string& category) const {
  const auto rule = bin_of.find(category);
  if (rule != bin_of.end()) return rule->second;
  if (!otherwise.empty()) return otherwise;
  return std::nullopt;
}

std::optional<std::string> SortingRules::BinFor(const std::string& category, double confidence) const {
  if (Rejects(confidence)) return reject_bin;
  return BinOf(category);
}

std::vector<std::string> SortingRules::NamedBins() const {
  std::set<std::string> bins;
  for (const auto& [category, bin] : bin_of) bins.insert(bin);
  if (!otherwise.empty()) bins.insert(otherwise);
  if (!reject_bin.empty()) bins.insert(reject_bin);
  return {bins.begin(), bins.end()};
}

}  // namespace sortcell::cell
