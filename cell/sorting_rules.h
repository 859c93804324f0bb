#pragma once
/// @file
/// Which bin each recognised object goes into: the user's rules (a bin per category, a bin for every
/// other category, and a reject bin for objects the model is not sure of), as data (scenes/cells/*.yaml).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "perception/reject_rule.h"

namespace sortcell::cell {

struct SortingRules {
  std::map<std::string, std::string> bin_of;  ///< Category -> bin.
  std::string otherwise;                      ///< The bin of every other category ("*"); empty: none.
  std::string reject_bin;                     ///< Where unsure objects go; empty: none.
  double reject_below = 0;                    ///< Recognised less surely than this (0-1): to the reject bin (0: never).

  /// Whether an object recognised with `confidence` goes to the reject bin.
  bool Rejects(double confidence) const {
    return !reject_bin.empty() && perception::Rejected(confidence, reject_below);
  }
  /// The bin the rules send `category` to; empty when no rule names one.
  std::optional<std::string> BinOf(const std::string& category) const;
  /// The bin for an object recognised as `category` with `confidence`: the reject bin below
  /// reject_below, else BinOf(category).
  std::optional<std::string> BinFor(const std::string& category, double confidence) const;
  /// Every bin a rule names (each once, sorted).
  std::vector<std::string> NamedBins() const;
};

}  // namespace sortcell::cell
