// Model/Data ownership, MuJoCo's handlers and divergence detection.
#include "sim/model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sim/mujoco_handlers.h"
#include "temp_dir.h"

namespace sortcell::sim {
namespace {

constexpr char kBall[] = R"(<mujoco><worldbody><geom type="plane" size="1 1 0.1"/>
  <body name="ball" pos="0 0 0.5"><freejoint/><geom type="sphere" size="0.05"/></body></worldbody></mujoco>)";

TEST(Model, MujocoErrorsThrowInsteadOfWaitingOnTheTerminal) {
  InstallMujocoHandlers();
  try {
    mju_error("deliberate");
    FAIL() << "expected MujocoError";
  } catch (const MujocoError& e) {
    EXPECT_NE(std::string(e.what()).find("deliberate"), std::string::npos);
  }
  const int before = MujocoWarningCount();
  mju_warning("deliberate warning");
  EXPECT_EQ(MujocoWarningCount(), before + 1);
  EXPECT_EQ(LastMujocoWarning(), "deliberate warning");
}

TEST(Model, StepReportsDivergence) {
  const Model model = Model::FromVirtualFiles({{"ball.xml", kBall}}, "ball");
  Data data(model);
  EXPECT_EQ(Step(model, data, 50).code, StepStatus::kOk);
  data->qvel[2] = std::numeric_limits<double>::quiet_NaN();
  const StepStatus status = Step(model, data, 1);
  EXPECT_EQ(status.code, StepStatus::kDiverged);
  EXPECT_NE(status.detail.find("badqvel"), std::string::npos) << status.detail;
  // The second divergence: MuJoCo's reset clears the counter before counting it, so it stays at 1;
  // the reset itself is seen.
  EXPECT_EQ(Step(model, data, 50).code, StepStatus::kOk);
  data->qvel[2] = std::numeric_limits<double>::quiet_NaN();
  const StepStatus again = Step(model, data, 3);
  EXPECT_EQ(again.code, StepStatus::kDiverged) << again.detail;
  EXPECT_EQ(FreeBodyNames(model), std::vector<std::string>{"ball"});
}

TEST(Model, BadFilesAreNamedInOneLine) {
  auto message = [](const std::string& path) {
    try {
      Model::FromFile(path);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const std::string missing = message("/nonexistent/scene.xml");
  EXPECT_NE(missing.find("'/nonexistent/scene.xml': file not found"), std::string::npos) << missing;
  const std::string dir = message(SORTCELL_SOURCE_DIR "/scenes");
  EXPECT_NE(dir.find("is a directory"), std::string::npos) << dir;
  const std::string bad = sortcell_test::TestTempDir() + "malformed.xml";
  FILE* f = std::fopen(bad.c_str(), "w");
  std::fputs("<mujoco><worldbody><geom type=\"sphere\"></worldbody>", f);
  std::fclose(f);
  const std::string malformed = message(bad);
  EXPECT_NE(malformed.find(bad), std::string::npos) << malformed;
  EXPECT_EQ(malformed.find('\n'), std::string::npos) << malformed;
  const Model model = Model::FromVirtualFiles({{"ball.xml", kBall}}, "ball");
  try {
    model.Id(mjOBJ_BODY, "nope");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no body named 'nope'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sortcell::sim
