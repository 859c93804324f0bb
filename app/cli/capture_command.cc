#include "app/cli/capture_command.h"

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "files/camera_file.h"
#include "files/data_dir.h"
#include "simcell/sim_layout.h"
#include "app/cli/cli_validators.h"
#include "files/output_dir.h"
#include "common/seeding.h"
#include "assets/image_file.h"
#include "perception/pcd_io.h"
#include "sim/kinect_camera.h"
#include "sim/model.h"
#include "sim/point_cloud.h"

namespace sortcell::app {
namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

void WriteImage(const std::filesystem::path& path, const cv::Mat& image) {
  if (!assets::WritePng(path, image)) throw std::runtime_error("cannot write '" + path.string() + "'");
}

cv::Mat DepthMillimetres(const cv::Mat& depth) {
  cv::Mat mm(depth.size(), CV_16UC1);
  for (int r = 0; r < depth.rows; ++r) {
    const float* z = depth.ptr<float>(r);
    uint16_t* out = mm.ptr<uint16_t>(r);
    for (int c = 0; c < depth.cols; ++c) {
      out[c] = std::isfinite(z[c]) ? static_cast<uint16_t>(std::clamp(std::lround(z[c] * 1000.0), 1L, 65535L)) : 0;
    }
  }
  return mm;
}

}  // namespace

CaptureSummary RunCapture(const CaptureOptions& options, const std::vector<std::string>& command_line) {
  const auto start = Clock::now();
  files::PrepareOutputDir(options.out);
  const sim::Model model = options.cell.empty()
                               ? files::LoadScene(options.scene)
                               : simcell::LoadCellScene(options.scene, files::ReadCellFile(options.cell));
  sim::Data data(model);
  sim::ResetToObserve(model, data);
  mj_forward(model.get(), data.get());

  sim::KinectCamera kinect(model, options.camera);
  std::mt19937_64 rng = EpisodeRng(options.seed, 0);
  const sim::KinectNoiseParams noise;
  const auto render_start = Clock::now();
  sim::FrameTruth truth;  // The capture command writes the label image and the camera's pose too.
  const sim::KinectFrame frame = kinect.Capture(data, options.no_noise ? nullptr : &noise, &rng, &truth);

  CaptureSummary summary;
  summary.render_wall_s = Seconds(render_start);
  summary.width = frame.intrinsics.width;
  summary.height = frame.intrinsics.height;
  const int valid = cv::countNonZero(frame.depth == frame.depth);  // NOLINT(misc-redundant-expression): NaN != NaN
  summary.valid_depth_fraction = static_cast<double>(valid) / frame.depth.total();

  cv::Mat bgr;
  cv::cvtColor(frame.rgb, bgr, cv::COLOR_RGB2BGR);
  WriteImage(options.out / "rgb.png", bgr);
  WriteImage(options.out / "depth.png", DepthMillimetres(frame.depth));
  WriteImage(options.out / "labels.png", truth.labels);
  const auto cloud = sim::ToOrganizedCloud(frame);
  perception::SaveCloud(options.out / "cloud.pcd", *cloud);

  nlohmann::json labels = {{"0", "none"}};
  nlohmann::json pixels = nlohmann::json::object();
  for (size_t i = 0; i < kinect.object_names().size(); ++i) {
    const std::string& name = kinect.object_names()[i];
    const int count = cv::countNonZero(truth.labels == static_cast<uint16_t>(i + 1));
    labels[std::to_string(i + 1)] = name;
    pixels[name] = count;
    if (count > 0) summary.visible_objects.emplace_back(name, count);
  }
  files::WriteJson(options.out / "labels.json", {{"labels", labels}, {"pixels", pixels}});
  files::WriteJson(options.out / "camera.json", files::CameraJson(options.camera, frame, truth.X_WC));
  summary.capture_wall_s = Seconds(start);
  files::WriteJson(options.out / "run.json", files::RunRecord(command_line, options.seed,
                                                              {{"command", "capture"},
                                                               {"scene", options.scene.string()},
                                                               {"noise", !options.no_noise},
                                                               {"render_wall_s", summary.render_wall_s},
                                                               {"capture_wall_s", summary.capture_wall_s}}));
  return summary;
}

void AddCaptureCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto options = std::make_shared<CaptureOptions>();
  CLI::App* cmd = app.add_subcommand(
      "capture",
      "Render one synthetic Kinect v1 frame of a scene (640x480, camera 'kinect') and write rgb.png, "
      "depth.png (16-bit mm, 0 = invalid), cloud.pcd (organized, camera optical frame), labels.png "
      "(ground-truth object ids, see labels.json), camera.json (intrinsics and X_WC) and run.json.");
  cmd->add_option("--scene", options->scene, "MJCF scene file, e.g. scenes/cell.xml")->required();
  cmd->add_option("--cell", options->cell, "Cell layout whose bins replace the scene's (scenes/cells/*.yaml)");
  cmd->add_option("--seed", options->seed, "Seed of the depth noise (uint64)")
      ->check(kUnsignedInteger)
      ->capture_default_str();
  cmd->add_flag("--no-noise", options->no_noise, "Ideal depth: no Kinect noise, quantisation or dropouts");
  cmd->add_option("--camera", options->camera, "Camera of the scene to capture")->capture_default_str();
  cmd->add_option("--out", options->out, "Output folder (created if missing)")->required();
  cmd->callback([&run, options, command_line] {
    run = [options, command_line] {
      const CaptureSummary s = RunCapture(*options, command_line);
      std::cout << "Captured " << options->scene.string() << " with camera '" << options->camera << "' at " << s.width
                << "x" << s.height
                << (options->no_noise ? " without noise"
                                      : " with Kinect noise (seed " + std::to_string(options->seed) + ")")
                << ": " << std::lround(100 * s.valid_depth_fraction) << " % of pixels have depth, "
                << s.visible_objects.size() << " objects visible (";
      for (size_t i = 0; i < s.visible_objects.size(); ++i) {
        std::cout << (i ? ", " : "") << s.visible_objects[i].first << " " << s.visible_objects[i].second << " px";
      }
      std::cout << "). Render " << std::lround(1000 * s.render_wall_s) << " ms, whole capture "
                << std::lround(1000 * s.capture_wall_s) << " ms. Files in " << options->out.string() << "/\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
