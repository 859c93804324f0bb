#pragma once
/// @file
/// How familiar a view is to a model: a calibrated score of "this view is like the views it was
/// trained on", for rejecting objects of no class the model knows.
///
/// The SVM's class probabilities cannot say this: far from every training view the RBF kernel is ~0,
/// and the probabilities fall back to the class biases, often at 0.9 or more (our paper model called
/// simulated lemons 'bottle' at 0.99+). A distance to the training set can. The score of a view is its
/// distance to the nearest training view in each of three blocks of the raw descriptor parts (hue;
/// saturation and value; CVFH shape), on square-rooted counts (a Hellinger-like distance that keeps
/// the object's size) with the colour counted per 5 mm voxel rather than per point (so the size does
/// not change with the sensor's distance), each block divided by its typical held-out distance, the largest of
/// the three. Familiarity is the share of held-out training views whose score is at least as large (a
/// conformal p-value): it is about uniform on (0, 1] for views like the training ones, so rejecting
/// below 0.05 rejects about 5 % of them, and small for views unlike any.
/// Held out means: each calibration view against the training views of other groups (other scenes
/// or instances, as the SVM's cross-validation groups them).

#include <Eigen/Core>

#include <vector>

#include "perception/descriptor.h"

namespace sortcell::perception {

struct Familiarity {
  /// The model's training views kept for the distance (square-rooted raw parts [HSV | CVFH], one per
  /// row, the HSV counts per voxel when colour_per_voxel): at most kMaxReference, evenly spaced over the
  /// training rows.
  Eigen::MatrixXf reference;
  /// Whether the colour counts are per voxel (every fit since 2026-12-06) or per point (model files of
  /// before, whose reference was kept that way; read as they were fitted).
  bool colour_per_voxel = true;
  Eigen::VectorXf block_scale;  ///< Per block: the 95th percentile of the held-out distances.
  std::vector<float> held_out;  ///< The calibration views' scores, ascending.

  static constexpr int kMaxReference = 2000;

  /// Whether it was fitted (a model file of before has none: every view is then familiar, 1).
  bool empty() const { return held_out.empty(); }

  /// Fits on the raw parts of the training views (rows of `raw_parts`, see RawParts) grouped by
  /// `groups` (a view is calibrated only against views of other groups).
  /// @throws std::invalid_argument for mismatched sizes, rows that are not raw parts, negative or
  ///         non-finite counts, or fewer than two groups.
  static Familiarity Fit(const Eigen::MatrixXf& raw_parts, const std::vector<int>& groups);

  /// The view's familiarity in (0, 1]; 1 when empty().
  /// @throws std::invalid_argument if `raw_parts` is not a RawParts vector.
  double Of(const Eigen::VectorXf& raw_parts) const;

  /// @throws std::invalid_argument naming what is inconsistent (the sizes of the three members).
  void Check() const;
};

/// [HSV counts | CVFH counts] (500) of ok parts, the input of Familiarity.
/// @throws std::invalid_argument as AssembleDescriptor for parts that are not ok.
Eigen::VectorXf RawParts(const DescriptorParts& parts);

}  // namespace sortcell::perception
