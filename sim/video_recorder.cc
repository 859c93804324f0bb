#include "sim/video_recorder.h"

#include <spdlog/fmt/fmt.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <stdexcept>

namespace sortcell::sim {
namespace {

// White text with a black outline: readable on any background.
void DrawText(cv::Mat& image, const std::string& text, cv::Point origin, double scale) {
  cv::putText(image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
  cv::putText(image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 2, cv::LINE_AA);
}

}  // namespace

VideoRecorder::VideoRecorder(const Model& model, const std::filesystem::path& path, const VideoOptions& options)
    : path_(path), options_(options), renderer_(model) {
  if (!(options.fps > 0)) throw std::invalid_argument("video: frames per second must be > 0");
  view_ = {model.Id(mjOBJ_CAMERA, options.camera), options.width, options.height};
  renderer_.CheckViewSize(options.width, options.height);
  // H.264 in MP4 through OpenCV's FFmpeg backend ("avc1" selects libx264 there).
  writer_.open(path.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'), options.fps,
               cv::Size(options.width, options.height));
  if (!writer_.isOpened()) throw std::runtime_error("video '" + path.string() + "': cannot open for H.264 writing");
}

void VideoRecorder::Update(const Data& data) {
  // Frame k shows the state at simulated time k / fps.
  if (writer_.isOpened() && data->time + 1e-9 >= frames_ / options_.fps) WriteFrame(data);
}

void VideoRecorder::WriteFrame(const Data& data) {
  const auto start = std::chrono::steady_clock::now();
  renderer_.Render(data, view_, rgb_, depth_);
  cv::cvtColor(rgb_, bgr_, cv::COLOR_RGB2BGR);
  const std::string line = fmt::format("t = {:6.2f} s{}{}", data->time, caption_.empty() ? "" : "   ", caption_);
  DrawText(bgr_, line, cv::Point(16, 36), 0.8);
  for (size_t i = 0; i < overlay_.size(); ++i) DrawText(bgr_, overlay_[i], cv::Point(16, 72 + 30 * static_cast<int>(i)), 0.65);
  if (!inset_.empty()) {
    const int width = bgr_.cols / 3;
    const int height = inset_.rows * width / inset_.cols;
    if (inset_scaled_.cols != width || inset_scaled_.rows != height) inset_scaled_.create(height, width, CV_8UC3);
    cv::resize(inset_, inset_scaled_, inset_scaled_.size(), 0, 0, cv::INTER_AREA);
    const cv::Rect where(bgr_.cols - width - 12, 12, width, std::min(height, bgr_.rows - 24));
    inset_scaled_(cv::Rect(0, 0, where.width, where.height)).copyTo(bgr_(where));
    cv::rectangle(bgr_, where, cv::Scalar(255, 255, 255), 2);
  }
  writer_.write(bgr_);
  ++frames_;
  render_wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void VideoRecorder::Close() {
  if (writer_.isOpened()) writer_.release();
}

}  // namespace sortcell::sim
