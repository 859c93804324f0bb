#pragma once
/// @file
/// How the paper's experiments split a dataset into training and test samples. A split is a list of
/// trials; most splits have one, the unseen-instance protocol of Lai et al. 2011 has several.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <vector>

#include "training/dataset.h"
#include "training/recognition.h"

namespace sortcell::training {

/// One training/test partition of a dataset's rows, and how to train on it.
struct Trial {
  std::vector<int> train, test;
  TrainRequest request;
  nlohmann::json description;  ///< What was held out, for results.json.
};

/// Experiment 1, the paper's: every fourth view (frame % 4 == 3) of every sequence is a test view.
Trial FrameSplit(const Dataset& d);

/// Experiment 1, unseen instances (Lai et al. 2011): in each trial one instance of every category is
/// held out for testing and the rest trains (cross-validation grouped by instance). Each category's
/// instances are held out in a seeded random order; with `trials` = 0 there are as many trials as the
/// largest category has instances, so every instance is held out at least once (a category with fewer
/// instances starts its order again).
/// @throws std::invalid_argument naming the category if one has a single instance, or for trials < 0.
std::vector<Trial> LeaveOneInstanceOutTrials(const Dataset& d, int trials, uint64_t seed);

/// Experiment 2: each (instance, elevation) sequence cut into three contiguous parts, two of the nine
/// parts per instance (seeded) are test parts; instance labels. Only the apple and orange instances,
/// as the paper, when the dataset has them; else every instance.
Trial SequenceSplit(const Dataset& d, uint64_t seed);

}  // namespace sortcell::training
