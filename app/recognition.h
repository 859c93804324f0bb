#pragma once
/// @file
/// Training and evaluating recognition models on datasets, and the reports in the paper's format.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "app/dataset.h"
#include "perception/metrics.h"
#include "perception/recognition_model.h"

namespace sortcell::app {

struct TrainRequest {
  perception::DescriptorKind descriptor = perception::DescriptorKind::kColorCvfhNorm;
  std::string label_kind = "category";  ///< "category" or "instance".
  /// Cross-validation groups: "sequence" (instance, elevation and third of the revolution; scenes by
  /// scene) or "instance" (for protocols that test on unseen instances).
  std::string group_by = "sequence";
  perception::SvmGrid grid;
};

/// Trains on the samples `rows` of `dataset` (all when empty). Classes: the labels of those rows,
/// in order of first appearance.
/// @throws std::invalid_argument for an unknown label kind or grouping, or what training throws.
perception::RecognitionModel TrainModel(const Dataset& dataset, std::vector<int> rows, const TrainRequest& request);

/// One model's results on a test set.
struct Evaluation {
  perception::DescriptorKind descriptor;
  perception::ConfusionMatrix confusion;
  perception::RecognitionMetrics metrics;
  double C = 0, gamma = 0, cv_accuracy = 0;
  int train_samples = 0, test_samples = 0;
  double mean_confidence = 0;
};

/// Classifies the samples `rows` of `dataset` (all when empty).
/// @throws std::invalid_argument naming the dataset if its descriptor parameters differ from the
///         model's, or a sample's label is not one of the model's classes.
Evaluation EvaluateModel(const perception::RecognitionModel& model, const Dataset& dataset, std::vector<int> rows,
                         const std::string& dataset_name);

/// {"macro_f1", "accuracy", "macro_recall", "macro_precision", "macro_accuracy", "per_class": {name:
/// {recall, precision, accuracy, f1}}, "confusion": {"classes", "counts", "percent"}, "svm": {...}}.
nlohmann::json EvaluationJson(const Evaluation& e);

/// Writes, for the evaluations side by side: tables.md (per class recall, precision, accuracy, F1 per
/// descriptor; confusion matrices in percent; macro averages), metrics.csv, and per descriptor
/// confusion_<name>.csv and confusion_<name>.png (heat map). Returns the Markdown.
std::string WriteRecognitionReport(const std::filesystem::path& dir, const std::string& title,
                                   const std::vector<Evaluation>& evaluations);

}  // namespace sortcell::app
