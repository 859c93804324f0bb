// Per-stage cost of one synthetic Kinect frame of the default cell (640x480): colour + depth render,
// segmentation render, depth conversion, noise model (with and without the correlation window, and the
// window alone), organized cloud, and the whole capture.
//   build/bench/kinect_benchmark
#include <benchmark/benchmark.h>

#include <memory>

#include "sim/kinect_camera.h"
#include "sim/model.h"
#include "sim/offscreen_renderer.h"
#include "sim/point_cloud.h"

namespace {

using namespace sortcell::sim;

struct Cell {
  Model model = Model::FromFile(SORTCELL_SOURCE_DIR "/scenes/cell.xml");
  Data data{model};
  Cell() {
    sortcell::sim::ResetToObserve(model, data);
    mj_forward(model.get(), data.get());
  }
};

Cell& TheCell() {
  static Cell cell;
  return cell;
}

RenderView KinectView(const Cell& cell) { return {cell.model.Id(mjOBJ_CAMERA, "kinect"), 640, 480}; }

void BM_RenderColourDepth(benchmark::State& state) {
  Cell& cell = TheCell();
  OffscreenRenderer renderer(cell.model);
  cv::Mat rgb, depth;
  for (auto _ : state) renderer.Render(cell.data, KinectView(cell), rgb, depth);
}
BENCHMARK(BM_RenderColourDepth)->Unit(benchmark::kMillisecond);

void BM_RenderSegmentation(benchmark::State& state) {
  Cell& cell = TheCell();
  OffscreenRenderer renderer(cell.model);
  cv::Mat ids;
  for (auto _ : state) renderer.RenderGeomIds(cell.data, KinectView(cell), ids);
}
BENCHMARK(BM_RenderSegmentation)->Unit(benchmark::kMillisecond);

void BM_LinearizeDepth(benchmark::State& state) {
  Cell& cell = TheCell();
  OffscreenRenderer renderer(cell.model);
  cv::Mat rgb, buffer;
  renderer.Render(cell.data, KinectView(cell), rgb, buffer);
  for (auto _ : state) benchmark::DoNotOptimize(LinearizeDepth(buffer, DepthRangeOf(cell.model)));
}
BENCHMARK(BM_LinearizeDepth)->Unit(benchmark::kMillisecond);

void BM_KinectNoise(benchmark::State& state) {
  Cell& cell = TheCell();
  KinectCamera kinect(cell.model);
  const KinectFrame clean = kinect.Capture(cell.data, nullptr, nullptr);
  KinectNoiseParams params;
  params.correlation_window_px = static_cast<int>(state.range(0));
  std::mt19937_64 rng(1);
  for (auto _ : state) benchmark::DoNotOptimize(ApplyKinectNoise(clean.depth, clean.intrinsics, params, rng));
}
// The argument is the correlation window (px; 0: off, the default).
BENCHMARK(BM_KinectNoise)->Arg(0)->Arg(9)->Unit(benchmark::kMillisecond);

void BM_CorrelationWindow(benchmark::State& state) {
  Cell& cell = TheCell();
  KinectCamera kinect(cell.model);
  const KinectFrame clean = kinect.Capture(cell.data, nullptr, nullptr);
  for (auto _ : state) benchmark::DoNotOptimize(CorrelationWindowDepth(clean.depth, 9, 0.02));
}
BENCHMARK(BM_CorrelationWindow)->Unit(benchmark::kMillisecond);

void BM_OrganizedCloud(benchmark::State& state) {
  Cell& cell = TheCell();
  KinectCamera kinect(cell.model);
  const KinectFrame frame = kinect.Capture(cell.data, nullptr, nullptr);
  for (auto _ : state) benchmark::DoNotOptimize(ToOrganizedCloud(frame));
}
BENCHMARK(BM_OrganizedCloud)->Unit(benchmark::kMillisecond);

void BM_FullCapture(benchmark::State& state) {
  Cell& cell = TheCell();
  KinectCamera kinect(cell.model);
  const KinectNoiseParams params;
  std::mt19937_64 rng(1);
  for (auto _ : state) {
    FrameTruth truth;  // The episode renders the label image for its scorer too.
    const KinectFrame frame = kinect.Capture(cell.data, &params, &rng, &truth);
    benchmark::DoNotOptimize(ToOrganizedCloud(frame));
  }
}
BENCHMARK(BM_FullCapture)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
