#pragma once
/// @file
/// What a model makes of samples of categories it was not trained on (a real banana under a produce
/// model): nothing to score them against, so instead what they were called and how confident the model
/// was, and what share a confidence threshold (--reject-below) would send to the reject bin.

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "training/dataset.h"
#include "perception/recognition_model.h"

namespace sortcell::training {

struct OutOfSetCategory {
  int samples = 0;
  std::map<std::string, int> called;  ///< Model class -> samples given it.
  std::vector<double> confidences;    ///< Per sample, sorted.
};

/// Per true category that is not one of the model's classes.
using OutOfSetReport = std::map<std::string, OutOfSetCategory>;

/// The rows of `dataset` whose label is one of the model's classes (in_set) and the others.
void SplitBySet(const perception::RecognitionModel& model, const Dataset& dataset, std::vector<int>& in_set,
                std::vector<int>& out_of_set);

/// Classifies the rows (samples of categories the model does not know).
OutOfSetReport ClassifyOutOfSet(const perception::RecognitionModel& model, const Dataset& dataset,
                                const std::vector<int>& rows);

/// {"<category>": {"samples", "called": {...}, "confidence": {"mean", "median", "p10", "p90", "max"},
/// "rejected_below": {"0.5": share, "0.6", "0.7", "0.8", "0.9"}}}.
nlohmann::json OutOfSetJson(const OutOfSetReport& report);

/// The same as a Markdown section for tables.md.
std::string OutOfSetMarkdown(const OutOfSetReport& report);

/// Every sample of one instance (known or not): what it was called and how confidently. For a known
/// instance the share called right; for either, the share a threshold would reject (a known one's
/// wrongly). Real views are judged instance by instance: one real apple is not the category.
struct InstanceResults {
  std::string category;
  bool known = false;  ///< Its category is one of the model's classes.
  int samples = 0, correct = 0;
  std::map<std::string, int> called;
  std::vector<double> confidences;  ///< Sorted.
};

/// Per instance (the category label of the model's kind decides known and correct).
std::map<std::string, InstanceResults> ClassifyByInstance(const perception::RecognitionModel& model,
                                                          const Dataset& dataset);

/// {"<instance>": {"category", "known", "samples", "correct_share", "called", "confidence": {...},
/// "histogram": [10 counts over 0-0.1, ..., 0.9-1], "rejected_below": {...}}}.
nlohmann::json InstanceJson(const std::map<std::string, InstanceResults>& report);

/// The same as a Markdown section for tables.md.
std::string InstanceMarkdown(const std::map<std::string, InstanceResults>& report);

}  // namespace sortcell::training
