#pragma once
/// @file
/// A trained recognition model: descriptor kind and parameters, class names, the SVM with its
/// scaling, and a format version, saved as one OpenCV FileStorage JSON file.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "perception/descriptor.h"
#include "perception/familiarity.h"
#include "perception/reject_rule.h"
#include "perception/svm_classifier.h"

namespace sortcell::perception {

/// Version 2 (2026-12-06): the familiarity counts colour per voxel (`colour_per_voxel`). A build reads
/// versions 1 and 2 (a version 1 file's familiarity counts colour per point); builds of before refuse 2.
inline constexpr int kModelFormatVersion = 2;

/// What a model's classes are: object categories ("bottle") or instances ("bottle1").
enum class LabelKind { kCategory, kInstance };

/// "category" or "instance": the spelling in model files, dataset reports and on the CLI.
const char* ToString(LabelKind kind);
/// @throws std::invalid_argument "unknown label kind '<name>' (expected category or instance)".
LabelKind ParseLabelKind(const std::string& name);

struct RecognitionModel {
  DescriptorKind descriptor = DescriptorKind::kColorCvfhNorm;
  DescriptorParams params;
  LabelKind label_kind = LabelKind::kCategory;  ///< What the classes are.
  std::vector<std::string> classes;
  SvmClassifier classifier;
  /// How like its training views a view is (empty in a model file of before: every view familiar).
  Familiarity familiarity;
  int train_samples = 0;   ///< Rows it was trained on.
  double cv_accuracy = 0;  ///< Grouped cross-validation accuracy of the chosen (C, gamma).

  struct Ranked {
    std::string name;
    double probability = 0;
  };
  struct Result {
    std::string name;
    /// The calibrated confidence: probability x familiarity. For views like the training ones it is
    /// about uniform below the class probability, so a reject threshold of 0.05 rejects about 5 % of
    /// them; an object unlike every training view gets a small one whatever the SVM says.
    double confidence = 0;
    double probability = 0;  ///< The SVM's probability of the class (Platt, pairwise coupling).
    double familiarity = 1;  ///< Familiarity::Of the view.
    int label = -1;
    std::vector<Ranked> ranked;  ///< Every class, most probable first.
  };
  /// Class name and confidence of one object's descriptor parts.
  /// @throws std::invalid_argument as AssembleDescriptor for parts whose status is not ok.
  Result Classify(const DescriptorParts& parts) const;
};

/// What a classification below a confidence threshold is called: the object is none of the model's
/// classes as far as it can tell (an unknown object, for the reject bin).
inline constexpr const char* kUnknownClass = "unknown";

/// One object recognised: described, then classified, the reject rule applied.
struct Recognition {
  DescriptorStatus status = DescriptorStatus::kOk;  ///< Not ok: too few points to describe (no result).
  std::string detail;                               ///< Why it could not be described.
  RecognitionModel::Result result;                  ///< When described.
  bool rejected = false;                            ///< Its confidence below reject_below.
  bool described() const { return status == DescriptorStatus::kOk; }
  /// The class it is called: the result's, or kUnknownClass when rejected.
  std::string category() const { return rejected ? kUnknownClass : result.name; }
};

/// Describes one object's cloud (camera frame) with the model's descriptor parameters and classifies it:
/// what the cell's policy and every command that names objects call.
Recognition Recognise(const Cloud& object_C, const RecognitionModel& model, double reject_below = 0);

/// @throws std::runtime_error naming the file if it cannot be written (e.g. a full disk).
void SaveModel(const std::filesystem::path& file, const RecognitionModel& model);

/// Loads and checks a model. With `expected`, a model for another descriptor is an error.
/// @throws std::invalid_argument "model '<file>': <what>" for a missing, damaged or foreign file, an
///         unsupported format version, an unknown label kind, inconsistent arrays, or another
///         descriptor than `expected`.
RecognitionModel LoadModel(const std::filesystem::path& file, std::optional<DescriptorKind> expected = std::nullopt);

}  // namespace sortcell::perception
