#pragma once
/// @file
/// A recognition dataset on disk: manifest.json (labels and provenance of every sample),
/// descriptors.csv (each sample's raw descriptor parts: 192 HSV + 308 CVFH values) and clouds/
/// (each sample's segmented cloud, camera frame, binary_compressed PCD).
///
/// The parts are raw, so one dataset serves all three descriptor kinds; the descriptor parameters
/// they were computed with are recorded and checked against a model's.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "perception/descriptor.h"
#include "perception/recognition_model.h"

namespace sortcell::training {

/// Version 2 (2026-12-06): samples say `fits_familiarity`. A build reads versions 1 and 2 (in version 1
/// every sample fits the familiarity); builds of before refuse 2, so none fits it on classifier-only views.
inline constexpr int kDatasetFormatVersion = 2;

struct Sample {
  int id = 0;
  std::string category, instance;
  std::string source = "turntable";  ///< "turntable", "turntable_occluded", "scene" or "rgbd-objects".
  double elevation_deg = 0;          ///< Turntable camera elevation (scenes: the cell's Kinect, 45).
  int frame = 0;                     ///< Turntable: view index in the revolution. Scene: object index.
  int scene = -1;                    ///< Scene number, -1 for turntable captures.
  std::string cloud;                 ///< Cloud file, relative to the dataset folder.
  int points = 0;
  double purity = 0;  ///< Fraction of the segment's pixels that belong to the labelled object.
  double iou = 0;     ///< Segment vs the object's ground-truth mask.
  /// Whether the view fits the model's familiarity as well as its classifier (SceneOptions); a manifest
  /// of before has no such key: true.
  bool fits_familiarity = true;
  perception::DescriptorParts parts;
};

struct Dataset {
  std::string object_set;  ///< The object set file it was made from.
  int views = 0;
  uint64_t seed = 0;
  perception::DescriptorParams params;
  std::vector<Sample> samples;
  nlohmann::json capture;  ///< How it was captured: counts, skipped captures, settings.

  /// The label of a sample by kind: its category or its instance.
  static const std::string& Label(const Sample& s, perception::LabelKind kind);
  /// Distinct labels of `kind`, in order of first appearance.
  std::vector<std::string> Labels(perception::LabelKind kind) const;
};

/// The descriptor parameters as a JSON object, one key per perception::VisitDescriptorParams field.
nlohmann::json DescriptorParamsJson(const perception::DescriptorParams& params);
/// @throws std::invalid_argument "<where>: <what>" for a missing or mistyped key.
perception::DescriptorParams DescriptorParamsFromJson(const nlohmann::json& json, const std::string& where);

/// Writes manifest.json and descriptors.csv into `dir` (clouds are written as they are captured).
/// @throws std::runtime_error naming the file if one cannot be written (e.g. a full disk).
void SaveDataset(const std::filesystem::path& dir, const Dataset& dataset);

/// @throws std::invalid_argument "dataset '<dir>': <what>" for a missing or damaged manifest or
///         descriptor file (not JSON, not a dataset manifest, a missing or mistyped key, a duplicate
///         sample id, a row that is not numbers or has the wrong number of columns), another format
///         version, or descriptors that do not match the manifest (unknown or missing samples).
Dataset LoadDataset(const std::filesystem::path& dir);

}  // namespace sortcell::training
