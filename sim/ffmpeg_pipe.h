#pragma once
/// @file
/// H.264 MP4 writing through the `ffmpeg` program (Debian's ffmpeg package), fed raw BGR frames on a
/// pipe. Why not OpenCV's videoio: linking it loads some 100 shared libraries (GStreamer, FFmpeg's
/// codecs) into every process that might write a video, and the dynamic loader's symbol lookups made
/// every start of `sortcell` (each test, each sweep worker) about 0.1-0.2 s slower; a child process
/// costs that only when a video is written.
#include <sys/types.h>

#include <filesystem>
#include <string>

namespace sortcell::sim {

class FfmpegPipe {
 public:
  /// Starts `ffmpeg` writing `path` from width x height BGR frames at `fps`.
  /// @throws std::runtime_error naming `path` if it cannot be created or ffmpeg cannot be started.
  FfmpegPipe(const std::filesystem::path& path, int width, int height, double fps);
  /// Writes one frame of width * height * 3 bytes.
  /// @throws std::runtime_error naming the file if ffmpeg has stopped taking frames.
  void Write(const unsigned char* bgr);
  /// Ends the stream and waits for ffmpeg to finish the file.
  /// @throws std::runtime_error naming the file if ffmpeg failed (its status and its last message).
  void Close();
  ~FfmpegPipe();
  FfmpegPipe(const FfmpegPipe&) = delete;
  FfmpegPipe& operator=(const FfmpegPipe&) = delete;

 private:
  std::filesystem::path path_;
  size_t frame_bytes_ = 0;
  int fd_ = -1;  // The pipe's write end.
  pid_t child_ = -1;
  std::filesystem::path messages_;  // ffmpeg's stderr, a temporary file: its last line goes into our error.
};

/// Writes the part of video `in` from `start_s` lasting `length_s` (cut short at its end) as an H.264
/// MP4 `out`, re-encoded so that it starts on the exact frame.
/// @throws std::runtime_error naming `out` if ffmpeg cannot start or fails (its last message).
void CutVideo(const std::filesystem::path& in, const std::filesystem::path& out, double start_s, double length_s);

}  // namespace sortcell::sim
