// Per-stage cost of the recognition chain on one 640x480 Kinect frame of the cell with its six objects
// (noise on): crop, plane, voxel, clustering, then per object normals, CVFH, HSV and the SVM. Prints a
// Markdown table of medians over the repetitions. Usage: perception_benchmark [MODEL.json] [repetitions]
// (without a model, one is trained on jittered copies of the frame's own segments to time prediction).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "perception/recognition_model.h"
#include "perception/segmentation.h"
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

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  const sim::Model model = sim::Model::FromFile(std::string(SORTCELL_SOURCE_DIR) + "/scenes/cell.xml");
  sim::Data data(model);
  sim::ResetToObserve(model, data);
  mj_forward(model.get(), data.get());
  sim::KinectCamera kinect(model);
  std::mt19937_64 rng(0);
  const sim::KinectNoiseParams noise;
  sim::FrameTruth truth;
  const sim::KinectFrame frame = kinect.Capture(data, &noise, &rng, &truth);
  const auto cloud = sim::ToOrganizedCloud(frame);

  std::vector<double> crop, plane, voxel, cluster, normals, cvfh, hsv, svm, total;
  size_t objects = 0, points = 0;
  perception::RecognitionModel recogniser;
  bool have_model = false;
  if (argc > 1) {
    recogniser = perception::LoadModel(argv[1], perception::DescriptorKind::kColorCvfhNorm);
    have_model = true;
  }
  for (int rep = 0; rep < repetitions + 1; ++rep) {
    const auto start = Clock::now();
    const auto r = perception::SegmentObjects(*cloud, truth.X_WC, nullptr);
    if (r.status != perception::SegmentationStatus::kOk) {
      std::fprintf(stderr, "perception_benchmark: the cell's frame does not segment: %s\n", r.detail.c_str());
      return 1;
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
    if (!have_model) {
      recogniser = ModelFromSegments(parts);
      have_model = true;
      continue;  // The first round trains the stand-in model and warms the caches.
    }
    for (const auto& p : parts) {
      const auto t = Clock::now();
      recogniser.Classify(p);
      s += std::chrono::duration<double>(Clock::now() - t).count();
    }
    total.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    crop.push_back(r.timings.crop_s);
    plane.push_back(r.timings.plane_s);
    voxel.push_back(r.timings.voxel_s);
    cluster.push_back(r.timings.cluster_s);
    normals.push_back(n);
    cvfh.push_back(c);
    hsv.push_back(h);
    svm.push_back(s);
    objects = r.segments.size();
    points = 0;
    for (const auto& segment : r.segments) points += segment.cloud_C->size();
  }
  std::printf("One 640x480 Kinect frame of scenes/cell.xml, %zu objects (%zu object points at full resolution), "
              "one core, median of %d runs, %d support vectors:\n\n",
              objects, points, repetitions, recogniser.classifier.support_vectors());
  std::printf("| stage | ms per frame |\n|---|---:|\n");
  const std::pair<const char*, double> rows[] = {
      {"crop (valid points, workspace box)", Median(crop)}, {"plane (RANSAC, points above it)", Median(plane)},
      {"voxel grid (5 mm)", Median(voxel)},                 {"Euclidean clustering", Median(cluster)},
      {"normals (all objects)", Median(normals)},           {"CVFH (all objects)", Median(cvfh)},
      {"HSV histogram (all objects)", Median(hsv)},         {"SVM (all objects)", Median(svm)}};
  double sum = 0;
  for (const auto& [name, s] : rows) {
    std::printf("| %s | %.2f |\n", name, 1000 * s);
    sum += s;
  }
  std::printf("| **total (measured end to end)** | **%.2f** |\n", 1000 * Median(total));
  std::printf("\nSum of the stages %.2f ms; the Kinect delivers a frame every 33.3 ms: the chain is %s.\n",
              1000 * sum, Median(total) < 1.0 / 30 ? "inside one frame period" : "slower than the frame rate");
  return 0;
}
