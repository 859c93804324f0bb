#pragma once
/// @file
/// `sortcell classify`: the category of one segmented object cloud (e.g. a segment_NN.pcd from
/// `sortcell segment`, or a real object's cloud), with its confidence and the runners-up.

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "perception/cloud.h"
#include "perception/recognition_model.h"

namespace sortcell::app {

/// What a model says of one object cloud: {"category", "confidence" (calibrated: probability x
/// familiarity), "probability" (the SVM's), "familiarity", "rejected", "top": [{"name", "probability"},
/// ...]}. Below `reject_below` (on the confidence) the category is perception::kUnknownClass (the
/// model's best guess stays first in "top").
/// @throws std::invalid_argument "<what>: <why>" if the cloud cannot be described (e.g. too few points).
nlohmann::json ClassifyObject(const perception::RecognitionModel& model, const perception::Cloud& object_C,
                              double reject_below, int top, const std::string& what);

void AddClassifyCommand(CLI::App& app, std::function<int()>& run);

}  // namespace sortcell::app
