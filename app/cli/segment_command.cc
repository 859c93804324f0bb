#include "app/cli/segment_command.h"

#include <spdlog/fmt/fmt.h>

#include <chrono>
#include <iostream>

#include "app/cli/classify_command.h"
#include "files/camera_file.h"
#include "files/output_dir.h"
#include "assets/image_file.h"
#include "perception/pcd_io.h"
#include "perception/segment_overlay.h"
#include "perception/segmentation.h"

namespace sortcell::app {
namespace {

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Classifies one segment into its segments.json entry; returns what the overlay shows. A segment too
// small to describe (a fragment) gets a null category and the reason.
std::string ClassifyEntry(const perception::RecognitionModel& model, const perception::Segment& segment,
                          double reject_below, nlohmann::json& entry) {
  try {
    const nlohmann::json r = ClassifyObject(model, *segment.cloud_C, reject_below, 3, "segment");
    for (const char* key : {"category", "confidence", "rejected", "top"}) entry[key] = r[key];
    return fmt::format("{} {:.2f}", r["category"].get<std::string>(), r["confidence"].get<double>());
  } catch (const std::invalid_argument& e) {
    entry["category"] = nullptr;
    entry["detail"] = e.what();
    return "?";
  }
}

// The cloud segmented as the options ask; a cloud without a table or without depth has nothing to
// segment: for this command, bad input.
perception::SegmentationResult SegmentPcd(const SegmentOptions& options, const perception::Cloud& cloud,
                                          const std::optional<Eigen::Isometry3d>& X_WC,
                                          const perception::Cloud* background) {
  perception::SegmentationParams params;
  params.clustering = ParseName(perception::SegmentationParams::kClusteringNames, options.clustering, "--clustering");
  perception::SegmentationResult result;
  try {
    result = perception::SegmentObjects(cloud, X_WC, background, params);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("PCD '" + options.pcd.string() + "': " + e.what());
  }
  if (result.status != perception::SegmentationStatus::kOk) {
    throw std::invalid_argument("PCD '" + options.pcd.string() + "': " + result.detail);
  }
  return result;
}

// Every segment's cloud and segments.json (classified with a model); returns what the overlay labels.
std::vector<std::string> WriteSegments(const SegmentOptions& options, const perception::SegmentationResult& result,
                                       const std::optional<perception::RecognitionModel>& model) {
  nlohmann::json segments = nlohmann::json::array();
  std::vector<std::string> labels;
  for (size_t i = 0; i < result.segments.size(); ++i) {
    const perception::Segment& s = result.segments[i];
    const std::string name = fmt::format("segment_{:02}.pcd", i);
    perception::SaveCloud(options.out / name, *s.cloud_C);
    segments.push_back({{"id", i},
                        {"points", s.cloud_C->size()},
                        {"voxels", s.voxels},
                        {"file", name},
                        {"centroid", Vec(s.centroid)},
                        {"bbox_min", Vec(s.bbox_min)},
                        {"bbox_max", Vec(s.bbox_max)},
                        {"principal_axis", Vec(s.principal_axes.col(0))}});
    if (model) {
      labels.push_back(fmt::format("{} {}", i, ClassifyEntry(*model, s, options.reject_below, segments.back())));
    }
  }
  const Eigen::Vector4d& plane = result.plane_C;
  files::WriteJson(options.out / "segments.json", {{"frame", result.world_frame ? "world" : "camera"},
                                                   {"plane_camera_frame", {plane[0], plane[1], plane[2], plane[3]}},
                                                   {"segments", segments}});
  return labels;
}

nlohmann::json SegmentRunJson(const SegmentOptions& options, bool organized,
                              const perception::SegmentationResult& result, double wall_s) {
  const auto& t = result.timings;
  return {
      {"command", "segment"},
      {"pcd", options.pcd.string()},
      {"camera", options.camera.string()},
      {"background", options.background.string()},
      {"model", options.model.string()},
      {"reject_below", options.reject_below},
      {"clustering", options.clustering},
      {"organized", organized},
      {"skipped",
       organized ? nlohmann::json::array() : nlohmann::json{"overlay.png (an unorganized cloud has no image)"}},
      {"segment_wall_s", wall_s},
      {"stages_wall_s", {{"crop", t.crop_s}, {"plane", t.plane_s}, {"voxel", t.voxel_s}, {"cluster", t.cluster_s}}}};
}

}  // namespace

int RunSegment(const SegmentOptions& options, const std::vector<std::string>& command_line) {
  const perception::Cloud::Ptr cloud = perception::LoadCloud(options.pcd, /*organized=*/false);
  if (!cloud->isOrganized() && !options.background.empty()) {
    throw std::invalid_argument(
        "--background: PCD '" + options.pcd.string() +
        "' is unorganized (height 1); background subtraction compares pixels of organized clouds");
  }
  std::optional<Eigen::Isometry3d> X_WC;
  if (!options.camera.empty()) X_WC = files::LoadCameraPose(options.camera);
  perception::Cloud::Ptr background;
  if (!options.background.empty()) background = perception::LoadCloud(options.background, /*organized=*/true);
  std::optional<perception::RecognitionModel> model;
  if (!options.model.empty()) model = perception::LoadModel(options.model);
  files::PrepareOutputDir(options.out);

  const auto start = std::chrono::steady_clock::now();
  const perception::SegmentationResult result = SegmentPcd(options, *cloud, X_WC, background.get());
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<std::string> labels = WriteSegments(options, result, model);
  // An unorganized cloud has no image to draw on: no overlay (the summary and run.json say so).
  if (!cloud->isOrganized()) std::filesystem::remove(options.out / "overlay.png");
  if (cloud->isOrganized()) {
    const cv::Mat overlay = perception::SegmentOverlay(*cloud, result.segments, labels);
    if (!assets::WritePng(options.out / "overlay.png", overlay)) {
      throw std::runtime_error("cannot write '" + (options.out / "overlay.png").string() + "'");
    }
  }
  files::WriteJson(options.out / "run.json",
                   files::RunRecord(command_line, 0, SegmentRunJson(options, cloud->isOrganized(), result, wall_s)));
  return static_cast<int>(result.segments.size());
}

void AddSegmentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* cmd = app.add_subcommand(
      "segment",
      "Segment the objects of an organized cloud (paper 2.1): invalid points out, workspace box (with --camera) "
      "and background subtraction (with --background), RANSAC supporting plane, 5 mm voxels, convex clusters "
      "(as the cell segments; --clustering euclidean: Euclidean clusters, which merge touching objects). Writes "
      "segment_NN.pcd (camera frame, full resolution), segments.json (world frame with "
      "--camera, else camera frame) and overlay.png. Works on real Kinect v1 PCDs (organized 640x480 "
      "XYZRGBA, any encoding) without --camera: the dominant plane is found and objects standing on it kept. "
      "Unorganized clouds are segmented too, without --background and without overlay.png.");
  cmd->add_option("--pcd", options->pcd, "Cloud (organized, e.g. cloud.pcd from sortcell capture, or unorganized)")
      ->required();
  cmd->add_option("--camera", options->camera, "camera.json with X_WC (from sortcell capture)");
  cmd->add_option("--background", options->background, "Organized cloud of the empty scene, same camera");
  cmd->add_option("--model", options->model,
                  "Recognition model (sortcell train): each segment's category, confidence and top 3 in "
                  "segments.json and on overlay.png");
  cmd->add_option("--reject-below", options->reject_below,
                  "With --model: a segment whose confidence is below this (0-1) is 'unknown'")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--clustering", options->clustering,
                  "euclidean: voxels within 15 mm join (touching objects merge); convex: supervoxels joined "
                  "across convex connections and cut at concave creases (LCCP), so touching objects come apart")
      ->check(CLI::IsMember(AllNames(perception::SegmentationParams::kClusteringNames)))
      ->capture_default_str();
  cmd->add_option("--out", options->out, "Output folder (created if missing)")->required();
  cmd->callback([&run, options, command_line] {
    run = [options, command_line] {
      const int n = RunSegment(*options, command_line);
      std::cout << "Segmented " << options->pcd.string() << ": " << n << " objects. Files in " << options->out.string()
                << "/"
                << (std::filesystem::exists(options->out / "overlay.png") ? "" : " (unorganized cloud: no overlay.png)")
                << "\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
