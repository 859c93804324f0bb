#pragma once
/// @file
/// Training and evaluating recognition models on datasets, and the reports in the paper's format.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "training/dataset.h"
#include "perception/metrics.h"
#include "perception/recognition_model.h"

namespace sortcell::training {

/// Cross-validation groups of the samples (neighbouring frames are near-duplicates, so never one
/// frame per group).
enum class Grouping {
  kSequence,  ///< Instance, elevation and third of the revolution; scene samples by scene.
  kInstance,  ///< Whole instances (for protocols that test on unseen instances).
};

/// "sequence" or "instance": the spelling on the CLI (--group-by).
const char* ToString(Grouping grouping);
/// @throws std::invalid_argument "unknown grouping '<name>' (expected sequence or instance)".
Grouping ParseGrouping(const std::string& name);

/// How experiment 1 splits its turntable data into training and test samples.
enum class ExperimentSplit {
  kPaper,           ///< Every fourth view of each turntable sequence is a test view (the paper's).
  kUnseenInstance,  ///< One instance per category held out for testing.
};

/// "paper" or "unseen-instance": the spelling on the CLI (--split) and in results.json.
const char* ToString(ExperimentSplit split);
/// @throws std::invalid_argument "unknown split '<name>' (expected paper or unseen-instance)".
ExperimentSplit ParseExperimentSplit(const std::string& name);

struct TrainRequest {
  perception::DescriptorKind descriptor = perception::DescriptorKind::kColorCvfhNorm;
  perception::LabelKind label_kind = perception::LabelKind::kCategory;
  Grouping group_by = Grouping::kSequence;  ///< Cross-validation groups.
  perception::SvmGrid grid;
};

/// Trains on the samples `rows` of `dataset` (all when empty). Classes: the labels of those rows,
/// in order of first appearance.
/// @throws std::invalid_argument for what training throws (e.g. too few groups or classes).
perception::RecognitionModel TrainModel(const Dataset& dataset, std::vector<int> rows, const TrainRequest& request);

/// One model's results on a test set.
struct Evaluation {
  perception::DescriptorKind descriptor;
  perception::ConfusionMatrix confusion;
  perception::RecognitionMetrics metrics;
  double C = 0, gamma = 0, cv_accuracy = 0;  ///< Pooled over trials: C and gamma of the first, mean CV accuracy.
  int train_samples = 0, test_samples = 0;   ///< Pooled: summed over the trials.
  double mean_confidence = 0;
  int trials = 1;  ///< How many evaluations were pooled into this one.
};

/// Classifies the samples `rows` of `dataset` (all when empty).
/// @throws std::invalid_argument naming the dataset if its descriptor parameters differ from the
///         model's (and which: "(<key>: dataset <value>, model <value>)"), or a sample's label is not
///         one of the model's classes.
/// @throws std::invalid_argument naming the dataset if its descriptors were computed with other
///         parameters than the model's.
void CheckDescriptorParams(const perception::RecognitionModel& model, const Dataset& dataset,
                           const std::string& dataset_name);

Evaluation EvaluateModel(const perception::RecognitionModel& model, const Dataset& dataset, std::vector<int> rows,
                         const std::string& dataset_name);

/// The evaluations of one descriptor on several trials as one: confusion counts summed (classes matched
/// by name, in the order of their first appearance), metrics of the sum.
/// @throws std::invalid_argument for none, or evaluations of different descriptors.
Evaluation PoolEvaluations(const std::vector<Evaluation>& trials);

/// {"macro_f1", "accuracy", "macro_recall", "macro_precision", "macro_accuracy", "per_class": {name:
/// {recall, precision, accuracy, f1}}, "confusion": {"classes", "counts", "percent"}, "svm": {...}}.
nlohmann::json EvaluationJson(const Evaluation& e);

/// Writes, for the evaluations side by side: tables.md (per class recall, precision, accuracy, F1 per
/// descriptor; confusion matrices in percent; macro averages), metrics.csv, and per descriptor
/// confusion_<name>.csv and confusion_<name>.png (heat map). Returns the Markdown. CSV fields are
/// quoted as RFC 4180 says (a class name may hold a comma). `preface` (Markdown) follows the title.
/// @throws std::runtime_error naming the file if one cannot be written (e.g. a full disk).
std::string WriteRecognitionReport(const std::filesystem::path& dir, const std::string& title,
                                   const std::vector<Evaluation>& evaluations, const std::string& preface = "");

}  // namespace sortcell::training
