// How well segmentation separates objects, as figures (not a test). In simulation first: random dense
// and clustered scenes of the paper's objects (30 % of the bottles and boxes lying), seen by the cell's
// Kinect with its noise, segmented as the cell does (calibrated camera pose, background subtraction),
// scored against the label image. Then on every labelled real capture in
// the given folders (the mOSD tabletop scenes: organized XYZRGB + a label per point), segmented as a real
// capture is (no camera pose: the dominant plane), each frame scored against its labels
// (perception/segmentation_scoring.h): objects found as one segment (IoU >= 0.5), merged, split,
// missed, and the overlap precision / recall / F-measure under one-to-one matching; then pooled per
// folder. Also the segmentation's wall time per frame.
// Usage: segmentation_benchmark [--scenes N] [--verbose] [--overlays DIR] [--pcl-supervoxels] [FOLDER ...]
//   (default: 50 sim scenes per mode; ../shared/real/mosd-learn and mosd-hard; --verbose: the objects
//   not found in each sim frame; --overlays: each such frame's convex segments as DIR/<mode><frame>.png;
//   --pcl-supervoxels: the convex clusters from PCL's SupervoxelClustering, the reference ours reproduce)
#include <algorithm>
#include <cstdlib>
#include <map>
#include <numeric>
#include <random>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "assets/image_file.h"
#include "cell/scene_observation.h"
#include "perception/pcd_io.h"
#include "perception/segment_overlay.h"
#include "perception/segmentation.h"
#include "perception/segmentation_scoring.h"
#include "sim/clutter_placement.h"
#include "sim/kinect_camera.h"
#include "sim/model.h"
#include "sim/point_cloud.h"

namespace {

namespace fs = std::filesystem;
using namespace sortcell;

void PrintScore(const char* name, const perception::SegmentationScore& s, double ms) {
  std::printf(
      "  %-14s objects %3d found %3d (%5.1f %%) merged %3d split %3d missed %3d | segments %3d | overlap P %5.1f R "
      "%5.1f F %5.1f | %6.1f ms\n",
      name, s.objects, s.found, 100 * s.FoundRate(), s.merged, s.split, s.missed, s.segments,
      100 * s.OverlapPrecision(), 100 * s.OverlapRecall(), 100 * s.OverlapF(), ms);
}

using Clustering = perception::SegmentationParams::Clustering;
const char* Name(Clustering c) { return c == Clustering::kConvex ? "convex (supervoxels + LCCP)" : "Euclidean"; }

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return 1000 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --verbose: the objects of a frame not found, each with its pixels, best IoU, share held by its best
// segment and that segment's make-up (object id: pixels; 0 is not an object).
void PrintFailures(size_t frame, const std::vector<int>& truth, const std::vector<std::vector<int>>& segments) {
  std::map<int, long> size;
  for (const int id : truth) {
    if (id > 0) ++size[id];
  }
  std::printf("   frame %zu:", frame);
  for (const auto& [id, n] : size) {
    if (n < 100) continue;
    size_t best = 0;
    long best_shared = -1;
    std::map<int, long> in_best;
    for (size_t k = 0; k < segments.size(); ++k) {
      std::map<int, long> count;
      for (const int px : segments[k]) ++count[truth[px]];
      if (count[id] > best_shared) best_shared = count[id], best = k, in_best = count;
    }
    const double iou = segments.empty() ? 0 : double(best_shared) / (n + segments[best].size() - best_shared);
    if (iou >= 0.5) continue;
    std::printf(" [obj %d n %ld iou %.2f holds %.2f seg %zu:", id, n, iou, double(best_shared) / n, best);
    for (const auto& [o, c] : in_best) std::printf(" %d:%ld", o, c);
    std::printf("]");
  }
  std::printf("\n");
}

// A rendered scene with its truth: an object id per pixel.
struct SimFrame {
  perception::Cloud::Ptr cloud;
  std::vector<int> truth;
  Eigen::Isometry3d X_WC;
};

// `scenes` random scenes of 4-6 of the cell's objects placed as `mode` says, 30 % of those that can lie lying.
std::vector<SimFrame> RenderScenes(const sim::Model& model, sim::PlacementMode mode, int scenes,
                                   perception::Cloud::Ptr& background) {
  sim::Data data(model);
  sim::KinectCamera kinect(model);
  const sim::KinectNoiseParams noise;
  std::mt19937_64 rng(static_cast<uint64_t>(mode) + 11);
  sim::ResetToObserve(model, data);
  const std::vector<std::string>& names = kinect.object_names();
  std::vector<int> bodies;
  std::vector<sim::ObjectShape> shapes;
  for (const auto& name : names) {
    bodies.push_back(model.Id(mjOBJ_BODY, name));
    shapes.push_back(sim::ObjectShapeOf(model, bodies.back()));
  }
  const auto park_all = [&] {
    for (size_t i = 0; i < bodies.size(); ++i) sim::ParkObject(model, data, bodies[i], static_cast<int>(i));
  };
  park_all();
  mj_forward(model.get(), data.get());
  background = sim::ToOrganizedCloud(kinect.Capture(data, &noise, &rng));
  sim::PlacementOptions options;
  options.mode = mode;
  options.lying_fraction = 0.3;
  std::vector<SimFrame> frames;
  for (int scene = 0; scene < scenes; ++scene) {
    std::vector<int> order(bodies.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    order.resize(std::uniform_int_distribution<size_t>(4, std::min<size_t>(6, bodies.size()))(rng));
    std::vector<sim::ObjectShape> chosen;
    for (const int o : order) chosen.push_back(shapes[o]);
    const auto poses = sim::SampleClutter(chosen, {}, sim::PlacementArea(), options, rng);
    if (!poses) continue;
    park_all();
    for (size_t k = 0; k < order.size(); ++k) sim::PlaceObject(model, data, bodies[order[k]], (*poses)[k], chosen[k]);
    mj_forward(model.get(), data.get());
    sim::FrameTruth truth;
    const sim::KinectFrame frame = kinect.Capture(data, &noise, &rng, &truth);
    SimFrame f{sim::ToOrganizedCloud(frame), {}, truth.X_WC};
    f.truth.assign(truth.labels.begin<uint16_t>(), truth.labels.end<uint16_t>());
    frames.push_back(std::move(f));
  }
  return frames;
}

void RunSim(const sim::Model& model, int scenes, bool verbose, const fs::path& overlays, bool pcl_supervoxels) {
  for (const sim::PlacementMode mode : {sim::PlacementMode::kDense, sim::PlacementMode::kClustered}) {
    perception::Cloud::Ptr background;
    const std::vector<SimFrame> frames = RenderScenes(model, mode, scenes, background);
    std::printf(
        "sim, %s scenes (%zu frames, 30 %% of bottles and boxes lying), cell segmentation "
        "(calibrated pose, background):\n",
        sim::ToString(mode), frames.size());
    for (const Clustering clustering : {Clustering::kEuclidean, Clustering::kConvex}) {
      perception::SegmentationParams params = cell::CellSegmentation(cell::CellLayout());
      params.clustering = clustering;
      params.convex.own_supervoxels = !pcl_supervoxels;
      std::vector<perception::SegmentationScore> scores;
      double total_ms = 0;
      for (const SimFrame& f : frames) {
        const auto start = std::chrono::steady_clock::now();
        const auto result = perception::SegmentObjects(*f.cloud, f.X_WC, background.get(), params);
        total_ms += MillisecondsSince(start);
        std::vector<std::vector<int>> segments;
        for (const auto& segment : result.segments) segments.push_back(segment.indices);
        scores.push_back(perception::ScoreSegmentation(f.truth, segments, 100));
        if (verbose && scores.back().found < scores.back().objects)
          PrintFailures(&f - frames.data(), f.truth, segments);
        if (!overlays.empty() && clustering == Clustering::kConvex && scores.back().found < scores.back().objects) {
          const std::string name = sim::ToString(mode) + std::to_string(&f - frames.data()) + ".png";
          const fs::path file = overlays / name;
          if (!sortcell::assets::WritePng(file, perception::SegmentOverlay(*f.cloud, result.segments))) {
            std::fprintf(stderr, "segmentation_benchmark: cannot write '%s'\n", file.c_str());
          }
        }
      }
      PrintScore(clustering == Clustering::kConvex ? "convex" : "Euclidean", perception::PoolScores(scores),
                 frames.empty() ? 0 : total_ms / frames.size());
    }
  }
}

int Run(int argc, char** argv) {
  std::vector<fs::path> folders;
  int scenes = 50;
  bool verbose = false, pcl_supervoxels = false;
  fs::path overlays;
  CLI::App cli("Scores the segmentation against the ground truth: random sim scenes and labelled real captures.",
               "segmentation_benchmark");
  cli.add_option("folders", folders,
                 "folders of labelled real captures (default: ../shared/real/mosd-learn, mosd-hard)");
  cli.add_option("--scenes", scenes, "sim scenes of each placement (0: none)")->check(WholeNumberAtLeast(0));
  cli.add_flag("--verbose", verbose, "list the sim objects not found");
  cli.add_option("--overlays", overlays, "write those frames' segments as images into this folder")
      ->check(CLI::ExistingDirectory);
  cli.add_flag("--pcl-supervoxels", pcl_supervoxels,
               "convex clusters from PCL's own supervoxels (the reference; the same figures, slower)");
  if (const auto exit_code = ParseBenchmarkArgs(cli, argc, argv)) return *exit_code;
  if (scenes > 0)
    RunSim(sim::Model::FromFile((fs::path(SORTCELL_SOURCE_DIR) / "scenes" / "cell.xml").string()), scenes, verbose,
           overlays, pcl_supervoxels);
  if (folders.empty()) {
    const fs::path real = fs::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real";
    folders = {real / "mosd-learn", real / "mosd-hard"};
  }
  for (const Clustering clustering : {Clustering::kEuclidean, Clustering::kConvex}) {
    perception::SegmentationParams params;
    params.clustering = clustering;
    params.convex.own_supervoxels = !pcl_supervoxels;
    std::printf("real, %s clusters on the dominant plane (no camera pose), against the labels:\n", Name(clustering));
    for (const fs::path& folder : folders) {
      if (!fs::is_directory(folder)) {
        std::fprintf(stderr, "segmentation_benchmark: '%s' is not a folder\n", folder.c_str());
        return 2;
      }
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.path().extension() == ".pcd") files.push_back(entry.path());
      }
      std::sort(files.begin(), files.end());
      std::printf("%s (%zu files)\n", folder.c_str(), files.size());
      std::vector<perception::SegmentationScore> scores;
      double total_ms = 0;
      for (const fs::path& file : files) {
        const std::vector<int> truth = perception::LoadMosdObjectIds(file);
        const perception::Cloud::Ptr cloud = perception::LoadCloud(file, true);
        if (truth.size() != cloud->size()) {
          std::fprintf(stderr, "segmentation_benchmark: '%s': labels and points differ in number\n", file.c_str());
          return 2;
        }
        const auto start = std::chrono::steady_clock::now();
        const perception::SegmentationResult result = perception::SegmentObjects(*cloud, std::nullopt, nullptr, params);
        const double ms = 1000 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        total_ms += ms;
        std::vector<std::vector<int>> segments;
        for (const auto& segment : result.segments) segments.push_back(segment.indices);
        // Objects of fewer than 100 labelled pixels (slivers behind others) are not counted.
        scores.push_back(perception::ScoreSegmentation(truth, segments, 100));
        PrintScore(file.filename().c_str(), scores.back(), ms);
      }
      PrintScore("pooled", perception::PoolScores(scores), files.empty() ? 0 : total_ms / files.size());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return RunBenchmark("segmentation_benchmark", [&] { return Run(argc, argv); });
}
