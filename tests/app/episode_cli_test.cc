// Bad input to `sortcell episode` and `sortcell sweep`: a one-line error naming the problem, exit
// code 2, and finished sweep results never touched.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_sortcell.h"
#include "source_tree.h"

namespace {

using sortcell_test::ExpectOneLineError;
using sortcell_test::RunSortcell;

using sortcell_test::kCell;
using sortcell_test::kSource;
const std::string kSet = kSource + "/scenes/objects/paper.yaml";

using sortcell_test::TempPath;

std::string Read(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(EpisodeCli, UnknownObjectSet) {
  ExpectOneLineError(
      RunSortcell("episode --scene " + kCell + " --object-set /nonexistent/set.yaml --out " + TempPath("a")),
      "object set '/nonexistent/set.yaml': file not found");
}

TEST(EpisodeCli, MissingModel) {
  ExpectOneLineError(
      RunSortcell("episode --scene " + kCell + " --model /nonexistent/m.model.json --out " + TempPath("b")),
      "/nonexistent/m.model.json");
}

TEST(EpisodeCli, NoCachedModelSaysHowToMakeOne) {
  // An empty model cache: no cached model there.
  const std::string cache = TempPath("models");
  std::filesystem::create_directories(cache);
  setenv("SORTCELL_MODEL_CACHE", cache.c_str(), 1);
  const auto r = RunSortcell("episode --scene " + kCell + " --object-set " + kSet + " --out " + TempPath("c"));
  unsetenv("SORTCELL_MODEL_CACHE");
  ExpectOneLineError(r, "no trained model at " + cache + "/paper-color-cvfh-norm.model.json");
  EXPECT_NE(r.err.find("--train-if-missing"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sortcell train --objects " + kSet + " --out " + cache + "/paper-color-cvfh-norm.model.json"),
            std::string::npos)
      << r.err;
}

TEST(EpisodeCli, BadSceneCountAndPlacement) {
  ExpectOneLineError(RunSortcell("episode --scene /nonexistent.xml --model x --out " + TempPath("d")),
                     "scene '/nonexistent.xml': file not found");
  ExpectOneLineError(RunSortcell("episode --scene " + kCell + " --place bottle1=0.5 --model x --out " + TempPath("e")),
                     "--place: expected NAME=x,y[,yaw[,lying]]");
  ExpectOneLineError(RunSortcell("episode --scene " + kCell + " --seed -1 --out " + TempPath("f")), "--seed");
  ExpectOneLineError(RunSortcell("episode --scene " + kCell + " --noise-seed -1 --out " + TempPath("f2")),
                     "--noise-seed");
}

TEST(EpisodeCli, BadVideoSize) {
  for (const char* size : {"1281x720", "1280", "0x720", "1280x720x2", "-640x360"}) {
    ExpectOneLineError(RunSortcell("episode --scene " + kCell + " --video-size " + size + " --out " + TempPath("g")),
                       "--video-size: expected WIDTHxHEIGHT with even positive numbers");
  }
}

TEST(EpisodeCli, BadSelfCalibrate) {
  ExpectOneLineError(RunSortcell("episode --scene " + kCell + " --self-calibrate maybe --out " + TempPath("h")),
                     "--self-calibrate");
}

TEST(CalibrateCli, BadSceneDisplacementAndSet) {
  ExpectOneLineError(RunSortcell("calibrate --scene /nonexistent.xml --out " + TempPath("cal_a")),
                     "scene '/nonexistent.xml': file not found");
  ExpectOneLineError(RunSortcell("calibrate --scene " + kCell + " --camera-shift -0.01 --out " + TempPath("cal_b")),
                     "camera jitter must be >= 0");
  ExpectOneLineError(RunSortcell("calibrate --scene " + kCell + " --set colour=red --out " + TempPath("cal_c")),
                     "--set: unknown key 'colour'");
  ExpectOneLineError(RunSortcell("calibrate --scene " + kCell + " --light-intensity 0 --out " + TempPath("cal_d")),
                     "--light-intensity: expected > 0");
}

class SweepBadInput : public ::testing::Test {
 protected:
  std::string Spec(const std::string& name, const std::string& body) {
    const std::string file = TempPath(name + ".yaml");
    std::ofstream(file) << "scene: " << kCell << "\nobject_set: " << kSet << "\n" << body;
    return file;
  }
};

TEST_F(SweepBadInput, MalformedSpecs) {
  ExpectOneLineError(RunSortcell("sweep " + Spec("unknown", "episodes: 2\nlighting: 3\n") + " --out " + TempPath("s1")),
                     "unknown key 'lighting'");
  ExpectOneLineError(RunSortcell("sweep " + Spec("type", "episodes: [2]\n") + " --out " + TempPath("s2")),
                     "key 'episodes': expected a non-negative integer");
  ExpectOneLineError(RunSortcell("sweep /nonexistent/spec.yaml --out " + TempPath("s3")), "file not found");
  ExpectOneLineError(RunSortcell("sweep " + Spec("ok", "episodes: 2\n") + " --shard 3/2 --out " + TempPath("s4")),
                     "--shard");
  ExpectOneLineError(RunSortcell("sweep " + Spec("ok2", "episodes: 2\n") + " -j 0 --out " + TempPath("s5")), "-j");
}

TEST_F(SweepBadInput, FinishedResultsAreNeverLost) {
  // A sweep folder with finished results (and a last line cut short by an interruption).
  const std::string out = TempPath("kept");
  std::filesystem::create_directories(out);
  const std::string spec = Spec("kept", "episodes: 2\n");
  std::filesystem::copy_file(spec, out + "/spec.yaml", std::filesystem::copy_options::overwrite_existing);
  const std::string results = "{\"episode\":0,\"status\":\"ok\"}\n{\"episode\":1,\"sta";
  std::ofstream(out + "/results.jsonl") << results;
  // Without --resume: refused, untouched.
  ExpectOneLineError(RunSortcell("sweep " + spec + " --out " + out), "add --resume");
  EXPECT_EQ(Read(out + "/results.jsonl"), results);
  // Another spec into the same folder: refused, untouched.
  ExpectOneLineError(RunSortcell("sweep " + Spec("other", "episodes: 3\n") + " --resume --out " + out), "another spec");
  EXPECT_EQ(Read(out + "/results.jsonl"), results);
  // A malformed spec: refused before anything is touched.
  ExpectOneLineError(RunSortcell("sweep " + Spec("bad", "episodes: -2\n") + " --resume --out " + out), "episodes");
  EXPECT_EQ(Read(out + "/results.jsonl"), results);
}

}  // namespace
