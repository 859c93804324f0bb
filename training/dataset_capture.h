#pragma once
/// @file
/// Making recognition datasets in simulation (ground truth is allowed here: it makes the labels).
///  - Turntable: each object instance alone at the turntable centre, seen by cameras at three
///    elevations (~30, 45, 60 degrees, ~1 m away), `views` views per revolution, as the RGB-D dataset
///    the paper used was recorded; lighting and a small pose jitter randomised, Kinect noise on.
///  - Scenes: the cell's Kinect looking at random arrangements of the set's objects (experiment 3).
/// Every capture is segmented with the perception pipeline (workspace box, background subtraction
/// against the empty cell, RANSAC plane, clusters); a segment is labelled with the object most of its
/// pixels show in the ground-truth label image.

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "training/dataset.h"
#include "files/object_set.h"

#include "perception/segmentation.h"
#include "sim/clutter_placement.h"

namespace sortcell::training {

struct TurntableOptions {
  int views = 36;  ///< Per revolution and elevation.
  uint64_t seed = 0;
  std::vector<double> elevations_deg{30, 45, 60};
  double distance_m = 1.0;                  ///< Camera to the aim point.
  Eigen::Vector3d centre_W{0.5, 0.0, 0.0};  ///< Turntable centre on the table.
  double aim_height_m = 0.06;               ///< Aim point above the centre.
  double jitter_m = 0.005;                  ///< Uniform +- position jitter.
  double yaw_jitter_rad = 0.05;             ///< Uniform +- yaw jitter on top of the view's angle.
  /// Per view, this many more samples of the same segment with part of the object hidden, as a nearer
  /// object hides it in a scene: the points beyond a random straight edge across the view are dropped,
  /// keeping a random 30-85 % of them (source "turntable_occluded"; same instance, elevation and frame,
  /// so grouped cross-validation keeps them with their view).
  int occluded_copies = 0;
};

struct SceneOptions {
  int scenes = 150;
  uint64_t seed = 0;
  int min_objects = 2, max_objects = 6;
  sim::PlacementArea area;  ///< Where objects stand: the episodes' distribution.
  /// Apart, touching or in groups, some lying, as episodes draw them: scene k is placed in mode
  /// modes[k % modes.size()] (placement.mode is not used).
  std::vector<sim::PlacementMode> modes{sim::PlacementMode::kSparse};
  sim::PlacementOptions placement;
  /// Each scene's objects' colours varied as the episodes' colour_jitter axis varies them, at a level
  /// drawn per scene from [0, colour_jitter] (0: the objects' own colours).
  double colour_jitter = 0;
  /// Each scene's depth noise (both sigmas) scaled by a factor drawn per scene from [1, depth_noise_max]
  /// (1: the Kinect's own), so that a model also knows the noisier depth of other sensors and rooms.
  double depth_noise_max = 1;
  /// Whether these views also fit the model's familiarity (TrainModel). False: they widen what the
  /// classifier knows (noisier depth, other colours) without teaching the familiarity to take in
  /// unknown objects that look like such views.
  bool fits_familiarity = true;
  /// How scenes are segmented: as the cell segments them, so touching objects come apart.
  perception::SegmentationParams::Clustering clustering = perception::SegmentationParams::Clustering::kConvex;
};

/// "sparse,dense,clustered": the modes as the dataset command takes them.
std::string PlacementModesText(const std::vector<sim::PlacementMode>& modes);

/// Renders, segments and describes the turntable views of every object of `set`; writes the clouds
/// into `dir`/clouds (the caller saves the rest with SaveDataset). Deterministic for a seed.
Dataset CaptureTurntable(const files::ObjectSet& set, const TurntableOptions& options,
                         const std::filesystem::path& dir);

/// The same for random cell scenes; a sample per labelled segment (scene and object index recorded).
Dataset CaptureScenes(const files::ObjectSet& set, const SceneOptions& options, const std::filesystem::path& dir);

}  // namespace sortcell::training
