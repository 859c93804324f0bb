// The review video's encoder: frames piped to the ffmpeg program make an MP4; a file that cannot be
// written and an ffmpeg that cannot be found are errors naming the file.
#include "sim/ffmpeg_pipe.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace sortcell::sim {
namespace {

std::string FailureOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no exception";
}

TEST(FfmpegPipe, FramesBecomeAnMp4) {
  sortcell_test::TempDir dir;
  const auto path = dir.path() / "clip.mp4";
  std::vector<unsigned char> frame(64 * 48 * 3);
  {
    FfmpegPipe pipe(path, 64, 48, 30);
    for (int k = 0; k < 10; ++k) {
      std::fill(frame.begin(), frame.end(), static_cast<unsigned char>(20 * k));
      pipe.Write(frame.data());
    }
    pipe.Close();
  }
  std::ifstream file(path, std::ios::binary);
  std::string head(12, '\0');
  file.read(head.data(), 12);
  EXPECT_EQ(head.substr(4, 4), "ftyp");  // An ISO media file's first box.
}

TEST(FfmpegPipe, AFileThatCannotBeWrittenIsNamed) {
  sortcell_test::TempDir dir;
  const auto path = dir.path() / "no_such_folder" / "clip.mp4";
  EXPECT_NE(FailureOf([&] { FfmpegPipe(path, 64, 48, 30); }).find(path.string()), std::string::npos);
}

TEST(FfmpegPipe, NoFfmpegIsAnErrorNamingTheFile) {
  sortcell_test::TempDir dir;
  const std::string path_variable = std::getenv("PATH");
  ::setenv("PATH", (dir.path() / "empty").c_str(), 1);
  const std::string error = FailureOf([&] { FfmpegPipe(dir.path() / "clip.mp4", 64, 48, 30); });
  ::setenv("PATH", path_variable.c_str(), 1);
  EXPECT_NE(error.find("clip.mp4"), std::string::npos) << error;
  EXPECT_NE(error.find("ffmpeg"), std::string::npos) << error;
}

// A stand-in `ffmpeg` on PATH that says something and exits with `status` (reading nothing).
class FakeFfmpeg {
 public:
  explicit FakeFfmpeg(int status) : path_variable_(std::getenv("PATH")) {
    const auto script = dir_.path() / "ffmpeg";
    std::ofstream(script) << "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit " << status << "\n";
    std::filesystem::permissions(script, std::filesystem::perms::owner_all);
    ::setenv("PATH", dir_.path().c_str(), 1);
  }
  ~FakeFfmpeg() { ::setenv("PATH", path_variable_.c_str(), 1); }
  std::filesystem::path Output() const { return dir_.path() / "clip.mp4"; }

 private:
  sortcell_test::TempDir dir_;
  std::string path_variable_;
};

TEST(FfmpegPipe, AFailedEncoderIsNamedWithItsStatusAndMessage) {
  const FakeFfmpeg fake(3);
  FfmpegPipe pipe(fake.Output(), 64, 48, 30);
  const std::string error = FailureOf([&] { pipe.Close(); });
  EXPECT_NE(error.find("clip.mp4"), std::string::npos) << error;
  EXPECT_NE(error.find("exit 3"), std::string::npos) << error;
  EXPECT_NE(error.find("Unknown encoder libx264"), std::string::npos) << error;
}

TEST(FfmpegPipe, FramesToAnEncoderThatStoppedAreAnError) {
  const FakeFfmpeg fake(1);
  FfmpegPipe pipe(fake.Output(), 320, 240, 30);  // 230 KB a frame: more than a pipe holds.
  const std::vector<unsigned char> frame(320 * 240 * 3, 0);
  const std::string error = FailureOf([&] {
    for (int k = 0; k < 4; ++k) pipe.Write(frame.data());
  });
  EXPECT_NE(error.find("stopped taking frames"), std::string::npos) << error;
  EXPECT_NE(FailureOf([&] { pipe.Close(); }).find("exit 1"), std::string::npos);
}

}  // namespace
}  // namespace sortcell::sim

namespace sortcell::sim {
namespace {

int FramesOf(const std::filesystem::path& video) {
  const std::string command =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 '" +
      video.string() + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  int frames = -1;
  if (std::fscanf(pipe, "%d", &frames) != 1) frames = -1;
  pclose(pipe);
  return frames;
}

TEST(FfmpegPipe, ACutKeepsItsSecondsAndAMissingVideoIsNamed) {
  sortcell_test::TempDir dir;
  const auto whole = dir.path() / "whole.mp4";
  {
    FfmpegPipe pipe(whole, 64, 48, 30);
    std::vector<unsigned char> frame(64 * 48 * 3);
    for (int k = 0; k < 90; ++k) {
      std::fill(frame.begin(), frame.end(), static_cast<unsigned char>(k));
      pipe.Write(frame.data());
    }
    pipe.Close();
  }
  CutVideo(whole, dir.path() / "cut.mp4", 1.0, 1.0);
  EXPECT_NEAR(FramesOf(dir.path() / "cut.mp4"), 30, 1);
  CutVideo(whole, dir.path() / "end.mp4", 2.5, 3.0);  // Cut short at the video's end.
  EXPECT_NEAR(FramesOf(dir.path() / "end.mp4"), 15, 1);
  const std::string error = FailureOf([&] { CutVideo(dir.path() / "none.mp4", dir.path() / "x.mp4", 0, 1); });
  EXPECT_NE(error.find("x.mp4"), std::string::npos) << error;
  EXPECT_NE(error.find("(cutting '" + (dir.path() / "none.mp4").string() + "')"), std::string::npos) << error;
}

}  // namespace
}  // namespace sortcell::sim
