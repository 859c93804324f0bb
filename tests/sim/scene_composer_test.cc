// Composing a cell with chosen object models, and the errors on the way.
#include "sim/scene_composer.h"

#include <gtest/gtest.h>

#include "error_of.h"

#include "sim/kinect_camera.h"
#include "sim/offscreen_renderer.h"

namespace {

using namespace sortcell::sim;
const std::filesystem::path kModels = SORTCELL_SOURCE_DIR "/models";

using sortcell_test::ErrorOf;

TEST(SceneComposer, ComposesTheCellWithChosenObjects) {
  const Model scene =
      LoadComposedCell(kModels, {kModels / "objects/apple1.inc.xml", kModels / "objects/box.inc.xml"}, "two objects");
  EXPECT_EQ(FreeBodyNames(scene), (std::vector<std::string>{"apple1", "box"}));
  EXPECT_NO_THROW(scene.Id(mjOBJ_SITE, "tcp"));  // The gripper sits on the flange.
  EXPECT_NO_THROW(scene.Id(mjOBJ_CAMERA, "kinect"));
  EXPECT_EQ(scene.compile_warning(), "");
}

TEST(SceneComposer, NamesAMissingModelFile) {
  const std::string e = ErrorOf([] { LoadComposedCell(kModels, {kModels / "objects/teapot.inc.xml"}, "my set"); });
  EXPECT_NE(e.find("my set: object model '"), std::string::npos) << e;
  EXPECT_NE(e.find("teapot.inc.xml' not found"), std::string::npos) << e;
}

TEST(SceneComposer, VirtualFilesThatDoNotCompileAreNamed) {
  const std::string e = ErrorOf([] { Model::FromVirtualFiles({{"bad.xml", "<mujoco><worldbody><geom/>"}}, "inline"); });
  EXPECT_NE(e.find("scene 'inline': "), std::string::npos) << e;
  EXPECT_NE(ErrorOf([] { Model::FromVirtualFiles({}, "nothing"); }).find("no files"), std::string::npos);
}

TEST(SceneComposer, RendererAndCameraRejectMisuse) {
  const Model scene = LoadComposedCell(kModels, {}, "empty cell");
  Data data(scene);
  mj_forward(scene.get(), data.get());
  OffscreenRenderer renderer(scene);
  cv::Mat rgb, depth;
  EXPECT_NE(ErrorOf([&] {
              renderer.Render(data, {scene->ncam, 640, 480}, rgb, depth);
            }).find("camera id"),
            std::string::npos);
  KinectCamera kinect(scene);
  const KinectNoiseParams noise;
  EXPECT_NE(ErrorOf([&] { kinect.Capture(data, &noise, nullptr); }).find("needs an rng"), std::string::npos);
  EXPECT_TRUE(kinect.object_names().empty());
}

}  // namespace
