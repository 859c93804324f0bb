// `sortcell pick --video`: an H.264 MP4 at 30 frames per simulated second that ordinary decoders
// read, and recording does not change the outcome.
#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include <filesystem>

#include "simcell/scripted_pick.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

namespace fs = std::filesystem;

TEST(PickVideo, H264At30FpsAndSameOutcome) {
  const fs::path dir = fs::path(sortcell_test::TestTempDir()) / "pick_video";
  simcell::PickOptions options;
  options.scene = fs::path(SORTCELL_SOURCE_DIR) / "scenes/cell.xml";
  options.object = "ball";
  options.bin = "ball";
  options.out = dir / "plain";
  const simcell::PickResult plain = simcell::RunPick(options, {"sortcell"});
  options.out = dir / "video";
  options.video = dir / "video" / "pick.mp4";
  const simcell::PickResult recorded = simcell::RunPick(options, {"sortcell"});
  EXPECT_EQ(plain.slip_mm, recorded.slip_mm);
  EXPECT_EQ(plain.cycle_time_s, recorded.cycle_time_s);
  EXPECT_EQ(recorded.status, "sorted");

  cv::VideoCapture video(options.video.string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(video.isOpened());
  const int fourcc = static_cast<int>(video.get(cv::CAP_PROP_FOURCC));
  const std::string codec{static_cast<char>(fourcc & 255), static_cast<char>((fourcc >> 8) & 255),
                          static_cast<char>((fourcc >> 16) & 255), static_cast<char>((fourcc >> 24) & 255)};
  EXPECT_TRUE(codec == "avc1" || codec == "h264" || codec == "H264") << codec;
  EXPECT_DOUBLE_EQ(video.get(cv::CAP_PROP_FPS), 30.0);
  EXPECT_EQ(video.get(cv::CAP_PROP_FRAME_WIDTH), 1280);
  EXPECT_EQ(recorded.video_frames, static_cast<int>(video.get(cv::CAP_PROP_FRAME_COUNT)));
  // 30 frames per simulated second: the whole run (settle, pick, settle) is on it.
  EXPECT_NEAR(recorded.video_frames, 30 * (recorded.cycle_time_s + 1.0), 3);
}

}  // namespace
}  // namespace sortcell::app
