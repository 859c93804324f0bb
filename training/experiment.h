#pragma once
/// @file
/// One of the paper's recognition experiments, whole: data captured (or
/// reused), CVFH, Color-CVFH and Color-CVFH (normalization) trained and evaluated side by side.
///  1: category level on the produce set (10 categories). Split "paper": every fourth view of each
///     turntable sequence is a test view (75/25, as the paper's frame split). Split
///     "unseen-instance" (Lai et al. 2011): trials, each holding out one instance per category for
///     testing, until every instance has been held out; the mean and spread of macro F1 reported.
///  2: instance level on the apple and orange instances: each elevation sequence cut into three contiguous
///     parts (nine per instance); two random parts per instance for testing, seven for training.
///  3: the real-scene experiment: trained on turntable views of the six paper objects (bottle, cup,
///     ball, others), tested on the objects segmented from random cell scenes.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "training/recognition.h"

namespace sortcell::training {

struct ExperimentOptions {
  int number = 0;
  ExperimentSplit split = ExperimentSplit::kPaper;  ///< Experiment 1 only.
  int trials = 0;  ///< Unseen-instance split only; 0: until every instance has been held out once.
  int views = 36;
  int scenes = 150;
  uint64_t seed = 0;
  std::filesystem::path out;
  /// Captured datasets; empty: out/data. Share it between experiments. A folder that holds one
  /// dataset (manifest.json) is the data of experiments 1 and 2 instead of the produce capture.
  std::filesystem::path data;
};

/// Runs the experiment and writes results.json, tables.md, metrics.csv, confusion_*.csv/.png,
/// models/ and run.json into options.out (datasets under options.data, reused when they match).
/// Returns results.json's content.
/// @throws std::invalid_argument for an unknown experiment, a split the experiment does not have,
///         trials without the unseen-instance split, or an unusable folder or dataset.
nlohmann::json RunExperiment(const ExperimentOptions& options, const std::vector<std::string>& command_line);

}  // namespace sortcell::training
