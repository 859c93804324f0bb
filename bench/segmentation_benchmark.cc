// How well segmentation separates objects, as figures (not a test): on every labelled real capture in
// the given folders (the mOSD tabletop scenes: organized XYZRGB + a label per point), segmented as a real
// capture is (no camera pose: the dominant plane), each frame scored against its labels
// (perception/segmentation_scoring.h): objects found as one segment (IoU >= 0.5), merged, split,
// missed, and the overlap precision / recall / F-measure under one-to-one matching; then pooled per
// folder. Also the segmentation's wall time per frame.
// Usage: segmentation_benchmark [FOLDER ...]   (default: ../shared/real/mosd-learn and mosd-hard)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "perception/pcd_io.h"
#include "perception/segmentation.h"
#include "perception/segmentation_scoring.h"

namespace {

namespace fs = std::filesystem;
using namespace sortcell;

void PrintScore(const char* name, const perception::SegmentationScore& s, double ms) {
  std::printf("  %-14s objects %3d found %3d (%5.1f %%) merged %3d split %3d missed %3d | segments %3d | overlap P %5.1f R %5.1f F %5.1f | %6.1f ms\n",
              name, s.objects, s.found, 100 * s.FoundRate(), s.merged, s.split, s.missed, s.segments,
              100 * s.OverlapPrecision(), 100 * s.OverlapRecall(), 100 * s.OverlapF(), ms);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<fs::path> folders;
  for (int i = 1; i < argc; ++i) folders.emplace_back(argv[i]);
  if (folders.empty()) {
    const fs::path real = fs::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real";
    folders = {real / "mosd-learn", real / "mosd-hard"};
  }
  for (const auto clustering : {perception::SegmentationParams::Clustering::kEuclidean,
                                 perception::SegmentationParams::Clustering::kConvex}) {
  perception::SegmentationParams params;
  params.clustering = clustering;
  std::printf("segmentation (%s clusters on the dominant plane, no camera pose) against the labels:\n",
              clustering == perception::SegmentationParams::Clustering::kConvex ? "convex (supervoxels + LCCP)" : "Euclidean");
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
