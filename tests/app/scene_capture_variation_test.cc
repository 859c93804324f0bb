// Training scenes varied as the default recipe varies them: the objects' colours jittered (`dataset
// --scenes N --colour-jitter J`) and the Kinect's depth noise scaled per scene (`--depth-noise-max M`). The
// same seed gives the same samples, the objects and their places are those of the plain scenes, what
// is varied differs from the plain scenes', and bad values are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "training/dataset.h"
#include "run_sortcell.h"
#include "source_tree.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using sortcell_test::ExpectOneLineError;
using sortcell_test::kSource;
using sortcell_test::RunSortcell;
using sortcell_test::TempPath;

sortcell::training::Dataset Scenes(const std::string& name, const std::string& extra) {
  const fs::path out = TempPath(name);
  const auto r = RunSortcell("dataset --objects " + kSource + "/scenes/objects/paper.yaml --scenes 3 --seed 5 --out " +
                             out.string() + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return sortcell::training::LoadDataset(out);
}

using Part = Eigen::VectorXf (*)(const sortcell::training::Sample&);
Eigen::VectorXf Hue(const sortcell::training::Sample& s) { return s.parts.hsv.head(90); }
Eigen::VectorXf Shape(const sortcell::training::Sample& s) { return s.parts.cvfh; }

// Of the objects both captures hold (by scene and instance): how many, and how many `differ` tells apart.
template <class Differ>
std::pair<int, int> CompareObjects(const sortcell::training::Dataset& a, const sortcell::training::Dataset& b,
                                   Part part, Differ differ) {
  std::map<std::pair<int, std::string>, Eigen::VectorXf> in_a;
  for (const auto& s : a.samples) in_a[{s.scene, s.instance}] = part(s);
  int compared = 0, differing = 0;
  for (const auto& s : b.samples) {
    const auto other = in_a.find({s.scene, s.instance});
    if (other == in_a.end()) continue;
    ++compared;
    differing += differ(other->second, part(s)) ? 1 : 0;
  }
  return {compared, differing};
}

TEST(ColourJitterCapture, SameSeedSameColoursOtherThanTheObjectsOwn) {
  const auto plain = Scenes("jitter_none", "");
  const auto jittered = Scenes("jitter_one", " --colour-jitter 1");
  const auto again = Scenes("jitter_again", " --colour-jitter 1");
  EXPECT_EQ(jittered.capture["colour_jitter"].get<double>(), 1.0);
  EXPECT_EQ(plain.capture["colour_jitter"].get<double>(), 0.0);
  ASSERT_EQ(jittered.samples.size(), again.samples.size());
  for (size_t i = 0; i < jittered.samples.size(); ++i) {
    EXPECT_EQ(jittered.samples[i].instance, again.samples[i].instance);
    EXPECT_TRUE(jittered.samples[i].parts.hsv.isApprox(again.samples[i].parts.hsv));
  }
  // The same objects in the same scenes (the jitter draws from a stream of its own), in other colours.
  const auto [compared, differ] = CompareObjects(plain, jittered, Hue, [](const auto& hue, const auto& other) {
    return (hue - other).cwiseAbs().sum() > 0.05 * hue.sum();
  });
  EXPECT_GE(compared, 6);
  EXPECT_GE(differ, compared / 2) << differ << " of " << compared;
}

TEST(ColourJitterCapture, BadValuesAreRefused) {
  const std::string set = kSource + "/scenes/objects/paper.yaml";
  ExpectOneLineError(
      RunSortcell("dataset --objects " + set + " --scenes 1 --colour-jitter 1.5 --out " + TempPath("j1")),
      "--colour-jitter");
  ExpectOneLineError(RunSortcell("dataset --objects " + set + " --colour-jitter 0.5 --out " + TempPath("j2")),
                     "--colour-jitter");
}

TEST(DepthNoiseCapture, SameSeedSameScenesSeenThroughOtherNoise) {
  const auto plain = Scenes("noise_one", "");
  const auto noisy = Scenes("noise_three", " --depth-noise-max 3");
  const auto again = Scenes("noise_again", " --depth-noise-max 3");
  EXPECT_EQ(noisy.capture["depth_noise_max"].get<double>(), 3.0);
  EXPECT_EQ(plain.capture["depth_noise_max"].get<double>(), 1.0);
  ASSERT_EQ(noisy.samples.size(), again.samples.size());
  for (size_t i = 0; i < noisy.samples.size(); ++i) {
    EXPECT_EQ(noisy.samples[i].instance, again.samples[i].instance);
    EXPECT_TRUE(noisy.samples[i].parts.cvfh.isApprox(again.samples[i].parts.cvfh));
  }
  // The same objects in the same scenes (the factor draws from a stream of its own), other shapes seen.
  const auto [compared, differ] = CompareObjects(
      plain, noisy, Shape, [](const auto& shape, const auto& other) { return !shape.isApprox(other, 1e-3F); });
  EXPECT_GE(compared, 6);
  EXPECT_GE(differ, compared / 2) << differ << " of " << compared;
}

TEST(DepthNoiseCapture, BadValuesAreRefused) {
  const std::string set = kSource + "/scenes/objects/paper.yaml";
  ExpectOneLineError(
      RunSortcell("dataset --objects " + set + " --scenes 1 --depth-noise-max 0.5 --out " + TempPath("n1")),
      "--depth-noise-max");
  ExpectOneLineError(RunSortcell("dataset --objects " + set + " --depth-noise-max 2 --out " + TempPath("n2")),
                     "--depth-noise-max");
}

}  // namespace
