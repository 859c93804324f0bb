#pragma once
/// @file
/// Off-screen video of a simulation for review: H.264 MP4 at a fixed number of frames per simulated
/// second from one of the model's cameras, with a caption line drawn on every frame. Rendering reads
/// the state only, so recording never changes what the simulation does. Only colour is rendered, only
/// at frame times; the text, the inset and the H.264 encoding run on a thread of their own, so the
/// simulation goes on while a frame is encoded.

#include <condition_variable>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "sim/ffmpeg_pipe.h"
#include "sim/model.h"
#include "sim/offscreen_renderer.h"

namespace sortcell::sim {

struct VideoOptions {
  std::string camera = "review";
  int width = 1280;
  int height = 720;
  double fps = 30;  ///< Frames per simulated second.
  /// Shadows and the floor's reflection: they cost 60 % of a frame's rendering on the CPU (software
  /// GL), so the review video leaves them out unless asked.
  bool shadows = false;
};

class VideoRecorder {
 public:
  /// @throws std::invalid_argument for an unknown camera, a size beyond the model's off-screen
  ///         buffer or fps <= 0; std::runtime_error naming `path` if the file cannot be opened for
  ///         H.264 writing.
  VideoRecorder(const Model& model, const std::filesystem::path& path, const VideoOptions& options = {});

  /// Writes a frame if the simulated time has reached the next frame time (call after every step).
  void Update(const Data& data);
  /// The caption drawn on the following frames (phase, object, ...).
  void SetCaption(std::string caption) { caption_ = std::move(caption); }
  /// Heads-up lines drawn under the caption on the following frames (empty: none).
  void SetOverlay(std::vector<std::string> lines) { overlay_ = std::move(lines); }
  /// A BGR image drawn in the top-right corner of the following frames, scaled to a third of the
  /// frame's width (empty: none), e.g. the robot's latest camera view.
  void SetInset(const cv::Mat& bgr) { inset_ = bgr.clone(); }
  /// Finishes the file, once the frames queued are written. Also done by the destructor.
  /// @throws std::runtime_error naming the file if the encoder failed.
  void Close();
  ~VideoRecorder();
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  int frames() const { return frames_; }
  /// Wall time of the simulation's thread spent on the video (rendering, and waiting when the encoder
  /// is behind) (s).
  double render_wall_s() const { return render_wall_s_; }

 private:
  // A rendered frame and what to draw on it, for the encoder thread.
  struct Frame {
    cv::Mat rgb;
    double time = 0;
    std::string caption;
    std::vector<std::string> overlay;
    cv::Mat inset;
  };
  void WriteFrame(const Data& data);
  void Encode();  // The encoder thread: draws and writes the queued frames in order.
  void Compose(Frame& frame);

  std::filesystem::path path_;
  VideoOptions options_;
  OffscreenRenderer renderer_;
  RenderView view_;
  std::unique_ptr<FfmpegPipe> encoder_pipe_;
  std::string encoder_error_;   // The encoder thread's failure, reported by Close().
  cv::Mat bgr_, inset_scaled_;  // The encoder thread's.
  std::string caption_;
  std::vector<std::string> overlay_;
  cv::Mat inset_;
  int frames_ = 0;
  double render_wall_s_ = 0;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;  // At most kQueued frames: the simulation waits when the encoder is behind.
  bool closing_ = false;
  std::thread encoder_;
};

}  // namespace sortcell::sim
