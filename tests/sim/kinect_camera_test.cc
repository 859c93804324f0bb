// The synthetic Kinect on rendered scenes: metric depth, the optical convention, X_WC, labels, colour.
#include "sim/kinect_camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <future>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/offscreen_renderer.h"
#include "sim/point_cloud.h"

namespace {

using namespace sortcell::sim;

// Camera at the origin looking along world +x (image right = world -y, image up = world +z), a wall
// whose front face is the plane x = 1.49, and a red ball up and to the right of the optical axis.
constexpr char kWallScene[] = R"(
<mujoco>
  <visual><global offwidth="640" offheight="480"/><quality offsamples="0"/></visual>
  <worldbody>
    <light pos="0 0 2" dir="1 0 -1" directional="true"/>
    <camera name="kinect" pos="0 0 0" xyaxes="0 -1 0 0 0 1" fovy="49.13"/>
    <geom name="wall" type="box" pos="1.5 0 0" size="0.01 3 3" rgba="0.7 0.7 0.7 1"/>
    <body name="ball" pos="1.2 -0.2 0.15"><freejoint/><geom type="sphere" size="0.05" rgba="1 0 0 1"/></body>
    <body name="turned" pos="1.2 0.25 -0.15" euler="0 0 0.5"><freejoint/><geom type="box" size="0.04 0.04 0.04"/></body>
  </worldbody>
</mujoco>)";

Model WallModel() { return Model::FromVirtualFiles({{"wall.xml", kWallScene}}, "wall scene"); }

// A capture with the simulator's truth beside it, for checks against ground truth.
struct Shot : KinectFrame {
  cv::Mat labels;
  Eigen::Isometry3d X_WC;
};
Shot Shoot(KinectCamera& kinect, const Data& data, const KinectNoiseParams* noise, std::mt19937_64* rng) {
  FrameTruth truth;
  Shot shot{kinect.Capture(data, noise, rng, &truth), truth.labels, truth.X_WC};
  return shot;
}

Shot CleanCapture(const Model& model, const std::string& keyframe = "") {
  Data data(model);
  if (!keyframe.empty()) mj_resetDataKeyframe(model.get(), data.get(), model.Id(mjOBJ_KEY, keyframe));
  mj_forward(model.get(), data.get());
  KinectCamera kinect(model);
  return Shoot(kinect, data, nullptr, nullptr);
}

TEST(KinectCamera, DepthIsMetricOverTheWholeImage) {
  const Model model = WallModel();
  const Shot frame = CleanCapture(model);
  const cv::Mat wall = frame.labels == 0;  // Pixels of the wall, not of the objects.
  double worst = 0;
  int n = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      if (!wall.at<unsigned char>(v, u)) continue;
      worst = std::max(worst, std::abs(frame.depth.at<float>(v, u) - 1.49));
      ++n;
    }
  }
  EXPECT_GT(n, 0.95 * 640 * 480);
  EXPECT_LT(worst, 0.0005) << "planar depth of a wall 1.49 m away";
  EXPECT_NEAR(frame.intrinsics.fy, 525.0, 0.5);
  EXPECT_EQ(frame.intrinsics.fx, frame.intrinsics.fy);
}

TEST(KinectCamera, PointsReprojectToTheirPixelAndTheOpticalFrameIsRightDownForward) {
  const Model model = WallModel();
  const Shot frame = CleanCapture(model);
  const auto cloud = ToOrganizedCloud(frame);
  ASSERT_EQ(cloud->width, 640u);
  ASSERT_EQ(cloud->height, 480u);
  const auto& k = frame.intrinsics;
  for (int v = 0; v < 480; v += 13) {
    for (int u = 0; u < 640; u += 13) {
      const auto& p = cloud->at(u, v);
      ASSERT_TRUE(std::isfinite(p.z));
      EXPECT_NEAR(k.fx * p.x / p.z + k.cx, u, 1e-3);
      EXPECT_NEAR(k.fy * p.y / p.z + k.cy, v, 1e-3);
    }
  }
  // X_WC: optical z = world +x, x = world -y, y = world -z.
  EXPECT_TRUE(frame.X_WC.linear().col(2).isApprox(Eigen::Vector3d::UnitX(), 1e-9));
  EXPECT_TRUE(frame.X_WC.linear().col(0).isApprox(-Eigen::Vector3d::UnitY(), 1e-9));
  EXPECT_TRUE(frame.X_WC.linear().col(1).isApprox(-Eigen::Vector3d::UnitZ(), 1e-9));
  // The ball (world -y = right, +z = up) is in the upper right of the image, and red.
  cv::Mat ball = frame.labels == 1;
  const cv::Moments m = cv::moments(ball, true);
  ASSERT_GT(m.m00, 100);
  const double u = m.m10 / m.m00, v = m.m01 / m.m00;
  EXPECT_NEAR(u, k.cx + k.fx * 0.2 / 1.2, 2.0);
  EXPECT_NEAR(v, k.cy - k.fy * 0.15 / 1.2, 2.0);
  const cv::Scalar colour = cv::mean(frame.rgb, ball);
  EXPECT_GT(colour[0], colour[1] + 80);
  EXPECT_GT(colour[0], colour[2] + 80);
  // World points of the ball lie on its sphere.
  for (int r = 0; r < 480; ++r) {
    for (int c = 0; c < 640; ++c) {
      if (!ball.at<unsigned char>(r, c)) continue;
      const auto& p = cloud->at(c, r);
      const Eigen::Vector3d p_W = frame.X_WC * Eigen::Vector3d(p.x, p.y, p.z);
      EXPECT_NEAR((p_W - Eigen::Vector3d(1.2, -0.2, 0.15)).norm(), 0.05, 0.002);
    }
  }
}

TEST(KinectCamera, TableTopLiesWhereTheCellSaysAndEveryObjectIsLabelled) {
  const Model cell = Model::FromFile(SORTCELL_SOURCE_DIR "/scenes/cell.xml");
  Data data(cell);
  mj_resetDataKeyframe(cell.get(), data.get(), cell.Id(mjOBJ_KEY, "observe"));
  mj_forward(cell.get(), data.get());
  KinectCamera kinect(cell);
  const Shot frame = Shoot(kinect, data, nullptr, nullptr);
  const auto cloud = ToOrganizedCloud(frame);

  // Unlabelled points above the workspace area are table: z = 0 in the world.
  int table = 0, off_plane = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const auto& p = cloud->at(u, v);
      if (!std::isfinite(p.z) || frame.labels.at<uint16_t>(v, u) != 0) continue;
      const Eigen::Vector3d p_W = frame.X_WC * Eigen::Vector3d(p.x, p.y, p.z);
      // |z| < 5 cm: the floor is also seen, under the table's front edge.
      if (p_W.x() < 0.3 || p_W.x() > 0.8 || std::abs(p_W.y()) > 0.3 || std::abs(p_W.z()) > 0.05) continue;
      ++table;
      if (std::abs(p_W.z()) > 0.001) ++off_plane;
    }
  }
  EXPECT_GT(table, 50000);
  EXPECT_LT(off_plane, table / 200) << "table points more than 1 mm off z = 0";

  // Each of the six objects is seen, and its labelled points lie around its body.
  ASSERT_EQ(kinect.object_names().size(), 6u);
  for (size_t i = 0; i < kinect.object_names().size(); ++i) {
    const std::string& name = kinect.object_names()[i];
    SCOPED_TRACE(name);
    const cv::Mat mask = frame.labels == static_cast<uint16_t>(i + 1);
    EXPECT_GT(cv::countNonZero(mask), 800);
    const Eigen::Vector3d p_WO = Eigen::Map<const Eigen::Vector3d>(data->xpos + 3 * cell.Id(mjOBJ_BODY, name));
    for (int v = 0; v < 480; v += 3) {
      for (int u = 0; u < 640; u += 3) {
        if (!mask.at<unsigned char>(v, u)) continue;
        const auto& p = cloud->at(u, v);
        const Eigen::Vector3d p_W = frame.X_WC * Eigen::Vector3d(p.x, p.y, p.z);
        EXPECT_LT((p_W - p_WO).head<2>().norm(), 0.07);
      }
    }
  }

  // The image is not blank, and objects have their colours.
  cv::Mat grey;
  cv::cvtColor(frame.rgb, grey, cv::COLOR_RGB2GRAY);
  cv::Scalar mean, stddev;
  cv::meanStdDev(grey, mean, stddev);
  EXPECT_GT(stddev[0], 20.0);
  auto colour_of = [&](const std::string& name) {
    for (size_t i = 0; i < kinect.object_names().size(); ++i) {
      if (kinect.object_names()[i] == name) return cv::mean(frame.rgb, frame.labels == static_cast<uint16_t>(i + 1));
    }
    return cv::Scalar();
  };
  const cv::Scalar bottle1 = colour_of("bottle1"), ball = colour_of("ball"), box = colour_of("box"),
                   bottle2 = colour_of("bottle2");
  EXPECT_GT(bottle1[1], bottle1[0]);  // green tea: green over red and blue
  EXPECT_GT(bottle1[1], bottle1[2]);
  EXPECT_GT(ball[0], ball[1] + 60);              // red ball
  EXPECT_GT(bottle2[0], bottle2[1]);             // amber/red bottle
  EXPECT_GT(box[0] + box[1] + box[2], 3 * 140);  // white box
}

// Same seed, same cloud; captured in two steps (KinectCamera::RenderClean, then ApplySensorModel), the same.
TEST(KinectCamera, SameSeedGivesTheSameCloud) {
  const Model model = WallModel();
  Data data(model);
  mj_forward(model.get(), data.get());
  KinectCamera kinect(model);
  const KinectNoiseParams noise;
  std::mt19937_64 a(42), b(42), c(43);
  const auto ca = ToOrganizedCloud(kinect.Capture(data, &noise, &a));
  const auto cb = ToOrganizedCloud(kinect.Capture(data, &noise, &b));
  const auto cc = ToOrganizedCloud(kinect.Capture(data, &noise, &c));
  // Field by field (a point's padding bytes are not initialised), NaN where NaN.
  const auto same = [](const pcl::PointCloud<pcl::PointXYZRGB>& p, const pcl::PointCloud<pcl::PointXYZRGB>& q) {
    if (p.size() != q.size()) return false;
    const auto eq = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    for (size_t i = 0; i < p.size(); ++i) {
      if (!eq(p[i].x, q[i].x) || !eq(p[i].y, q[i].y) || !eq(p[i].z, q[i].z) || p[i].r != q[i].r || p[i].g != q[i].g ||
          p[i].b != q[i].b) {
        return false;
      }
    }
    return true;
  };
  EXPECT_TRUE(same(*ca, *cb));
  EXPECT_FALSE(same(*ca, *cc));

  // In two steps (the clean render here, the sensor model on another thread), draw for draw the same,
  // the truth too; and the stream is left where Capture leaves it.
  std::mt19937_64 d(42);
  FrameTruth truth_whole, truth_split;
  const KinectFrame whole = kinect.Capture(data, &noise, &d, &truth_whole);
  std::mt19937_64 e(42);
  KinectFrame clean = kinect.RenderClean(data, &truth_split);
  const KinectFrame split =
      std::async(std::launch::async, [&] { return KinectCamera::ApplySensorModel(std::move(clean), noise, e); }).get();
  EXPECT_TRUE(same(*ToOrganizedCloud(whole), *ToOrganizedCloud(split)));
  EXPECT_TRUE(same(*ToOrganizedCloud(whole), *ca)) << "the label render draws nothing from the stream";
  EXPECT_EQ(cv::norm(truth_whole.labels, truth_split.labels, cv::NORM_INF), 0);
  EXPECT_TRUE(truth_whole.X_WC.matrix() == truth_split.X_WC.matrix());
  EXPECT_EQ(d(), e());
}

TEST(KinectCamera, MissingCameraAndTooSmallBufferAreNamed) {
  const Model model = WallModel();
  try {
    KinectCamera kinect(model, "nope");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no camera named 'nope'"), std::string::npos) << e.what();
  }
  try {
    KinectCamera kinect(model, "kinect", 1280, 960);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("offwidth"), std::string::npos) << e.what();
  }
}

TEST(KinectCamera, AScenePastTheRenderersTextureLimitIsRefusedNotDrawnWhite) {
  // MuJoCo 2.2.2 draws 100 textures per context; the 101st and later came out white.
  const auto scene_with = [](int count) {
    std::string textures, materials;
    for (int i = 0; i < count; ++i) {
      textures += "<texture name=\"t" + std::to_string(i) +
                  "\" type=\"2d\" builtin=\"flat\" width=\"4\" height=\"4\" rgb1=\"1 0 0\"/>";
      materials += "<material name=\"m" + std::to_string(i) + "\" texture=\"t" + std::to_string(i) + "\"/>";
    }
    std::string scene = kWallScene;
    scene.replace(scene.find("<worldbody>"), 0, "<asset>" + textures + materials + "</asset>");
    return Model::FromVirtualFiles({{"textures.xml", scene}}, "textured scene");
  };
  const Model at_limit = scene_with(kMaxTextures);
  EXPECT_NO_THROW(KinectCamera kinect(at_limit));
  const Model model = scene_with(kMaxTextures + 1);
  try {
    KinectCamera kinect(model);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("101 textures, more than the 100"), std::string::npos) << e.what();
  }
}

}  // namespace
