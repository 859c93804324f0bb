#pragma once
/// @file
/// A trained recognition model: descriptor kind and parameters, class names, the SVM with its
/// scaling, and a format version, saved as one OpenCV FileStorage JSON file.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "perception/descriptor.h"
#include "perception/svm_classifier.h"

namespace sortcell::perception {

inline constexpr int kModelFormatVersion = 1;

struct RecognitionModel {
  DescriptorKind descriptor = DescriptorKind::kColorCvfhNorm;
  DescriptorParams params;
  std::string label_kind = "category";  ///< What the classes are: "category" or "instance".
  std::vector<std::string> classes;
  SvmClassifier classifier;
  int train_samples = 0;     ///< Rows it was trained on.
  double cv_accuracy = 0;    ///< Grouped cross-validation accuracy of the chosen (C, gamma).

  /// Class name and confidence of one object's descriptor parts.
  struct Result {
    std::string name;
    double confidence = 0;
    int label = -1;
  };
  Result Classify(const DescriptorParts& parts) const;
};

/// @throws std::runtime_error naming the file if it cannot be written.
void SaveModel(const std::filesystem::path& file, const RecognitionModel& model);

/// Loads and checks a model. With `expected`, a model for another descriptor is an error.
/// @throws std::invalid_argument "model '<file>': <what>" for a missing, damaged or foreign file, an
///         unsupported format version, inconsistent arrays, or another descriptor than `expected`.
RecognitionModel LoadModel(const std::filesystem::path& file, std::optional<DescriptorKind> expected = std::nullopt);

/// Whether two descriptor parameter sets give the same descriptors (every field equal).
bool SameDescriptorParams(const DescriptorParams& a, const DescriptorParams& b);

}  // namespace sortcell::perception
