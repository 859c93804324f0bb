// Per-stage cost of the cell's recognition chain on a 640x480 Kinect frame of the cell with its six
// objects (noise on), as placed in scenes/cell.xml and heaped touching (dense): crop, plane, voxel,
// convex clustering, then per segment normals, CVFH, HSV and the SVM (and the clustering four times
// more, in turn: as it is, without its split at creases, to show what the split costs, with PCL's
// supervoxels, and with PCL's supervoxels computing their voxel normals too, to show what ours save).
// Prints a Markdown table of
// medians over the repetitions per frame. Usage: perception_benchmark [--model MODEL.json] [--repetitions N]
// (without a model, one is trained on jittered copies of the frame's own segments to time prediction).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "files/cell_file.h"
#include "simcell/sim_layout.h"
#include "bench_args.h"
#include "cell/bin_fill.h"
#include "cell/scene_observation.h"
#include "perception/recognition_model.h"
#include "perception/segmentation.h"
#include "sim/clutter_placement.h"
#include "sim/kinect_camera.h"
#include "sim/model.h"
#include "sim/point_cloud.h"

namespace {

using namespace sortcell;
using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

perception::RecognitionModel ModelFromSegments(const std::vector<perception::DescriptorParts>& parts) {
  std::mt19937_64 rng(1);
  std::normal_distribution<float> jitter(1.0f, 0.05f);
  const int copies = 100;
  Eigen::MatrixXf x(parts.size() * copies, 500);
  std::vector<int> y, groups;
  for (size_t o = 0; o < parts.size(); ++o) {
    const Eigen::VectorXf d = perception::AssembleDescriptor(parts[o], perception::DescriptorKind::kColorCvfhNorm);
    for (int c = 0; c < copies; ++c) {
      for (int k = 0; k < 500; ++k) x(o * copies + c, k) = d[k] * jitter(rng);
      y.push_back(static_cast<int>(o) % 4);
      groups.push_back(c % 6);
    }
  }
  perception::RecognitionModel m;
  m.classes = {"bottle", "cup", "ball", "others"};
  m.classifier = perception::SvmClassifier::Train(x, y, groups, 4);
  return m;
}

struct Frame {
  std::string name;
  perception::Cloud::Ptr cloud;
  Eigen::Isometry3d X_WC;
};

// The cell's six objects as scenes/cell.xml places them, and heaped touching (dense, 30 % of the
// bottles and the box lying); and the empty cell for background subtraction, as the cell captures it.
std::vector<Frame> Frames(const sim::Model& model, perception::Cloud::Ptr& background) {
  sim::Data data(model);
  sim::ResetToObserve(model, data);
  sim::KinectCamera kinect(model);
  std::mt19937_64 rng(0);
  const sim::KinectNoiseParams noise;
  std::vector<Frame> frames;
  const auto capture = [&](const std::string& name) {
    mj_forward(model.get(), data.get());
    sim::FrameTruth truth;
    frames.push_back({name, sim::ToOrganizedCloud(kinect.Capture(data, &noise, &rng, &truth)), truth.X_WC});
  };
  capture("as placed in scenes/cell.xml");
  std::vector<int> bodies;
  std::vector<sim::ObjectShape> shapes;
  for (const auto& name : kinect.object_names()) {
    bodies.push_back(model.Id(mjOBJ_BODY, name));
    shapes.push_back(sim::ObjectShapeOf(model, bodies.back()));
  }
  sim::PlacementOptions dense;
  dense.mode = sim::PlacementMode::kDense;
  dense.lying_fraction = 0.3;
  const auto poses = sim::SampleClutter(shapes, {}, sim::PlacementArea(), dense, rng);
  for (size_t i = 0; poses && i < bodies.size(); ++i) sim::PlaceObject(model, data, bodies[i], (*poses)[i], shapes[i]);
  capture("dense, touching");
  for (size_t i = 0; i < bodies.size(); ++i) sim::ParkObject(model, data, bodies[i], static_cast<int>(i));
  mj_forward(model.get(), data.get());
  background = sim::ToOrganizedCloud(kinect.Capture(data, &noise, &rng));
  return frames;
}

struct StageTimes {
  std::vector<double> crop, plane, voxel, cluster, normals, cvfh, hsv, svm, total;
  std::vector<double> bins;  // The cell's look into its bins (cell::BinFill::See), besides the chain.
  // The clustering again after the chain, as it is, without its split at creases, with PCL's supervoxels,
  // and with PCL's supervoxels computing their voxel normals too: in turn, each first in every fourth
  // repetition (a second pass over a frame runs warmer than the chain's first).
  std::vector<double> cluster_again, cluster_unsplit, cluster_pcl_supervoxels, cluster_pcl_normals;
  int round = 0;
  size_t objects = 0, points = 0;
};

// One pass of the chain over `frame`; false if it does not segment.
bool TimeOnce(const Frame& frame, const perception::Cloud& background, const perception::SegmentationParams& params,
              const cell::CellLayout& layout, perception::RecognitionModel& recogniser, bool& have_model,
              StageTimes& t) {
  const auto start = Clock::now();
  const auto r = perception::SegmentObjects(*frame.cloud, frame.X_WC, &background, params);
  if (r.status != perception::SegmentationStatus::kOk) {
    std::fprintf(stderr, "perception_benchmark: the frame '%s' does not segment: %s\n", frame.name.c_str(),
                 r.detail.c_str());
    return false;
  }
  std::vector<perception::DescriptorParts> parts;
  double n = 0, c = 0, h = 0, s = 0;
  for (const auto& segment : r.segments) {
    perception::DescriptorParts p = perception::ComputeDescriptorParts(*segment.cloud_C);
    n += p.normals_s;
    c += p.cvfh_s;
    h += p.hsv_s;
    if (p.status == perception::DescriptorStatus::kOk) parts.push_back(std::move(p));  // Fragments: timed only.
  }
  if (!have_model) {  // The first round trains the stand-in model and warms the caches.
    recogniser = ModelFromSegments(parts);
    have_model = true;
    return true;
  }
  for (const auto& p : parts) {
    const auto t0 = Clock::now();
    recogniser.Classify(p);
    s += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  t.total.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  cell::BinFill bins(layout);
  const auto bins_start = Clock::now();
  bins.See(*frame.cloud, frame.X_WC, cell::ArmCapsules(layout.q_observe, std::nullopt));
  t.bins.push_back(std::chrono::duration<double>(Clock::now() - bins_start).count());
  perception::SegmentationParams variants[4] = {params, params, params, params};
  variants[1].convex.split_at_creases = false;
  variants[2].convex.own_supervoxels = false;
  variants[3].convex.own_voxel_normals = false;
  std::vector<double>* times[4] = {&t.cluster_again, &t.cluster_unsplit, &t.cluster_pcl_supervoxels,
                                   &t.cluster_pcl_normals};
  for (int k = 0; k < 4; ++k) {
    const int v = (t.round + k) % 4;
    times[v]->push_back(
        perception::SegmentObjects(*frame.cloud, frame.X_WC, &background, variants[v]).timings.cluster_s);
  }
  ++t.round;
  t.crop.push_back(r.timings.crop_s);
  t.plane.push_back(r.timings.plane_s);
  t.voxel.push_back(r.timings.voxel_s);
  t.cluster.push_back(r.timings.cluster_s);
  t.normals.push_back(n);
  t.cvfh.push_back(c);
  t.hsv.push_back(h);
  t.svm.push_back(s);
  t.objects = r.segments.size();
  t.points = 0;
  for (const auto& segment : r.segments) t.points += segment.cloud_C->size();
  return true;
}

void PrintTable(const Frame& frame, const StageTimes& t, int repetitions, int support_vectors) {
  std::printf(
      "\nOne 640x480 Kinect frame of the cell's six objects, %s: %zu segments (%zu object points at full "
      "resolution), segmented as the cell does (calibrated pose, background, convex clusters), one core, "
      "median of %d runs, %d support vectors:\n\n",
      frame.name.c_str(), t.objects, t.points, repetitions, support_vectors);
  std::printf("| stage | ms per frame |\n|---|---:|\n");
  const std::pair<const char*, double> rows[] = {
      {"crop (valid points, workspace box, background)", Median(t.crop)},
      {"plane (RANSAC, points above it)", Median(t.plane)},
      {"voxel grid (5 mm)", Median(t.voxel)},
      {"convex clustering (supervoxels + LCCP + crease split)", Median(t.cluster)},
      {"normals (all segments)", Median(t.normals)},
      {"CVFH (all segments)", Median(t.cvfh)},
      {"HSV histogram (all segments)", Median(t.hsv)},
      {"SVM (all segments)", Median(t.svm)}};
  double sum = 0;
  for (const auto& [name, s] : rows) {
    std::printf("| %s | %.2f |\n", name, 1000 * s);
    sum += s;
  }
  std::printf("| **total (measured end to end)** | **%.2f** |\n", 1000 * Median(t.total));
  std::printf("\nSum of the stages %.2f ms; the Kinect delivers a frame every 33.3 ms: the chain is %s.\n", 1000 * sum,
              Median(t.total) < 1.0 / 30 ? "inside one frame period" : "slower than the frame rate");
  std::printf(
      "Besides the chain, the cell's look into its bins from the same frame (height maps, cell::BinFill::See): "
      "%.2f ms.\n",
      1000 * Median(t.bins));
  std::printf(
      "The convex clustering timed again after the chain, in turn with three variants: as it is %.2f ms; without "
      "its split at creases (split_at_creases off) %.2f ms (the split: %.2f ms); with PCL's supervoxels "
      "(own_supervoxels off) %.2f ms (ours save %.2f ms); with PCL's supervoxels computing their voxel normals "
      "themselves too (own_voxel_normals off) %.2f ms (ours save %.2f ms).\n",
      1000 * Median(t.cluster_again), 1000 * Median(t.cluster_unsplit),
      1000 * (Median(t.cluster_again) - Median(t.cluster_unsplit)), 1000 * Median(t.cluster_pcl_supervoxels),
      1000 * (Median(t.cluster_pcl_supervoxels) - Median(t.cluster_again)), 1000 * Median(t.cluster_pcl_normals),
      1000 * (Median(t.cluster_pcl_normals) - Median(t.cluster_again)));
}

// Reads [--model MODEL.json] [--repetitions N]; runs every frame.
int Run(int argc, char** argv) {
  int repetitions = 20;
  std::string model_path;
  CLI::App cli("Times the cell's perception chain (segment, describe, classify) on two Kinect frames, one core.",
               "perception_benchmark");
  cli.add_option("--model", model_path, "a trained model (MODEL.json) instead of a stand-in SVM")
      ->check(CLI::ExistingFile);
  cli.add_option("--repetitions", repetitions, "timed runs per frame; the median is printed")
      ->check(WholeNumberAtLeast(1));
  if (const auto exit_code = ParseBenchmarkArgs(cli, argc, argv)) return *exit_code;
  const sim::Model model = sim::Model::FromFile(std::string(SORTCELL_SOURCE_DIR) + "/scenes/cell.xml");
  perception::Cloud::Ptr background;
  const std::vector<Frame> frames = Frames(model, background);
  perception::RecognitionModel recogniser;
  bool have_model = !model_path.empty();  // TimeOnce trains one from the first frame otherwise.
  if (have_model) recogniser = perception::LoadModel(model_path, perception::DescriptorKind::kColorCvfhNorm);
  const cell::CellLayout layout = simcell::ReadCellLayout(model, files::ReadCellFile(files::DefaultCellFile()));
  const perception::SegmentationParams params = cell::CellSegmentation(layout);
  for (const Frame& frame : frames) {
    StageTimes t;
    for (int rep = 0; rep < repetitions + 1; ++rep) {
      if (!TimeOnce(frame, *background, params, layout, recogniser, have_model, t)) return 1;
    }
    PrintTable(frame, t, static_cast<int>(t.total.size()), recogniser.classifier.support_vectors());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return RunBenchmark("perception_benchmark", [&] { return Run(argc, argv); });
}
