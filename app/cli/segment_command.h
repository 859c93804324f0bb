#pragma once
/// @file
/// `sortcell segment`: objects of one organized cloud (a capture or a real Kinect PCD), written as one
/// PCD per cluster, segments.json and overlay.png.

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sortcell::app {

struct SegmentOptions {
  std::filesystem::path pcd;
  std::filesystem::path camera;      ///< camera.json; empty: camera frame, dominant plane.
  std::filesystem::path background;  ///< Organized PCD of the empty scene; empty: none.
  std::filesystem::path model;       ///< Recognition model: every segment classified; empty: none.
  double reject_below = 0;           ///< With a model: below this confidence a segment is "unknown".
  /// "convex" or "euclidean" (SegmentationParams::Clustering). Convex by default: it separates touching
  /// objects (the segmentation benchmark's real mosd-hard captures: overlap F 86.3 against 62.0).
  std::string clustering = "convex";
  std::filesystem::path out;
};

/// Returns the number of segments written.
/// @throws std::invalid_argument for bad input files (one line naming the file), including a cloud
///         without a valid point or without a supporting plane (the segmentation's detail), or an
///         unusable output folder.
int RunSegment(const SegmentOptions& options, const std::vector<std::string>& command_line);

void AddSegmentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
