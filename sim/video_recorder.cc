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

// Frames rendered ahead of the encoder at most: bounds the memory (2.7 MB each at 1280x720).
constexpr size_t kQueued = 8;

}  // namespace

VideoRecorder::VideoRecorder(const Model& model, const std::filesystem::path& path, const VideoOptions& options)
    : path_(path), options_(options), renderer_(model) {
  if (!(options.fps > 0)) throw std::invalid_argument("video: frames per second must be > 0");
  view_ = {model.Id(mjOBJ_CAMERA, options.camera), options.width, options.height, options.shadows, options.shadows};
  renderer_.CheckViewSize(options.width, options.height);
  encoder_pipe_ = std::make_unique<FfmpegPipe>(path, options.width, options.height, options.fps);
  encoder_ = std::thread([this] { Encode(); });
}

VideoRecorder::~VideoRecorder() {
  try {
    Close();
  } catch (...) {  // A destructor must not throw; Close() called first reports it.
  }
}

void VideoRecorder::Update(const Data& data) {
  // Frame k shows the state at simulated time k / fps.
  if (!closing_ && data->time + 1e-9 >= frames_ / options_.fps) WriteFrame(data);
}

void VideoRecorder::WriteFrame(const Data& data) {
  const auto start = std::chrono::steady_clock::now();
  Frame frame;
  renderer_.RenderRgb(data, view_, frame.rgb);
  frame.time = data->time;
  frame.caption = caption_;
  frame.overlay = overlay_;
  frame.inset = inset_;  // Shares the pixels: SetInset replaces inset_ with a new clone.
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < kQueued; });
    queue_.push_back(std::move(frame));
  }
  changed_.notify_all();
  ++frames_;
  render_wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void VideoRecorder::Compose(Frame& frame) {
  cv::cvtColor(frame.rgb, bgr_, cv::COLOR_RGB2BGR);
  const std::string line =
      fmt::format("t = {:6.2f} s{}{}", frame.time, frame.caption.empty() ? "" : "   ", frame.caption);
  DrawText(bgr_, line, cv::Point(16, 36), 0.8);
  for (size_t i = 0; i < frame.overlay.size(); ++i) {
    DrawText(bgr_, frame.overlay[i], cv::Point(16, 72 + 30 * static_cast<int>(i)), 0.65);
  }
  if (!frame.inset.empty()) {
    const int width = bgr_.cols / 3;
    const int height = frame.inset.rows * width / frame.inset.cols;
    cv::resize(frame.inset, inset_scaled_, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    const cv::Rect where(bgr_.cols - width - 12, 12, width, std::min(height, bgr_.rows - 24));
    inset_scaled_(cv::Rect(0, 0, where.width, where.height)).copyTo(bgr_(where));
    cv::rectangle(bgr_, where, cv::Scalar(255, 255, 255), 2);
  }
}

void VideoRecorder::Encode() {
  while (true) {
    Frame frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;  // Closing, and everything written.
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();
    if (!encoder_error_.empty()) continue;  // Failed: the frames are let go so the simulation goes on.
    Compose(frame);
    try {
      encoder_pipe_->Write(bgr_.data);
    } catch (const std::exception& e) {
      encoder_error_ = e.what();
    }
  }
}

void VideoRecorder::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closing_) return;
    closing_ = true;
  }
  changed_.notify_all();
  if (encoder_.joinable()) encoder_.join();
  // ffmpeg's own end first: when it stopped taking frames, its status says why.
  try {
    encoder_pipe_->Close();
  } catch (const std::exception& e) {
    throw std::runtime_error(encoder_error_.empty() ? e.what() : encoder_error_ + "; " + e.what());
  }
  if (!encoder_error_.empty()) throw std::runtime_error(encoder_error_);
}

}  // namespace sortcell::sim
