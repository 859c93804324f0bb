// An episode with --video: an H.264 MP4 at 30 frames per simulated second that ordinary decoders
// read, and the same outcome as without it.
#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "run_sortcell.h"

namespace {

nlohmann::json RunEpisode(const std::string& name, const std::string& extra) {
  const std::string out = sortcell_test::TestTempDir() + "episode_video_" + name;
  std::filesystem::remove_all(out);
  const auto r =
      sortcell_test::RunSortcell(std::string("episode --scene ") + SORTCELL_SOURCE_DIR + "/scenes/cell.xml --model " +
                                 SORTCELL_TEST_MODEL + " --seed 7 --objects 2 --out " + out + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out + "/metrics.json");
  return nlohmann::json::parse(in);
}

TEST(EpisodeVideo, PlayableAndDoesNotChangeTheOutcome) {
  const std::string video = sortcell_test::TestTempDir() + "episode_video.mp4";
  std::filesystem::remove(video);
  nlohmann::json with = RunEpisode("with", "--video " + video);
  nlohmann::json without = RunEpisode("without", "");
  cv::VideoCapture capture(video, cv::CAP_FFMPEG);
  ASSERT_TRUE(capture.isOpened());
  EXPECT_NEAR(capture.get(cv::CAP_PROP_FPS), 30.0, 0.01);
  const double sim_time = with["summary"]["sim_time_s"].get<double>();
  EXPECT_NEAR(capture.get(cv::CAP_PROP_FRAME_COUNT), 30 * sim_time, 3);
  EXPECT_EQ(with["summary"]["video_frames"].get<int>(), static_cast<int>(capture.get(cv::CAP_PROP_FRAME_COUNT)));
  const int fourcc = static_cast<int>(capture.get(cv::CAP_PROP_FOURCC));
  EXPECT_EQ(std::string({static_cast<char>(fourcc & 255), static_cast<char>((fourcc >> 8) & 255),
                         static_cast<char>((fourcc >> 16) & 255), static_cast<char>((fourcc >> 24) & 255)}),
            "avc1");
  cv::Mat frame;
  ASSERT_TRUE(capture.read(frame));
  EXPECT_EQ(frame.cols, 1280);
  EXPECT_EQ(frame.rows, 720);
  // Recording reads the state only: the same items, attempts and simulated time.
  EXPECT_EQ(with["items"], without["items"]);
  EXPECT_EQ(with["attempts"], without["attempts"]);
  EXPECT_EQ(with["summary"]["sim_time_s"], without["summary"]["sim_time_s"]);
}

}  // namespace
