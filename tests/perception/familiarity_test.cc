// Familiarity: calibrated on held-out groups, about uniform for views like the training ones, small
// for a view unlike every one; bad input refused; kept in the model file; part of the confidence.
#include "perception/familiarity.h"

#include <gtest/gtest.h>

#include "error_of.h"
#include "perception/recognition_model.h"
#include "temp_dir.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <random>

namespace sortcell::perception {
namespace {

using sortcell_test::ErrorOf;
constexpr int kRaw = kHsvBins + kCvfhBins;

// Raw parts of a view of class `c`: a hue peak of its own, grey-ish saturation and value, a shape
// histogram of its own, all counts noisy.
Eigen::VectorXf View(int c, std::mt19937_64& rng) {
  std::normal_distribution<float> noise(0.0f, 4.0f);
  Eigen::VectorXf v(kRaw);
  for (int k = 0; k < kRaw; ++k) {
    float mean = 5;
    if (k < kHueBins) mean = (k / 10 == c) ? 80.0f : 0.0f;
    if (k >= kHsvBins) mean = ((k - kHsvBins) % 3 == c) ? 30.0f : 10.0f;
    v[k] = std::max(0.0f, mean + noise(rng));
  }
  return v;
}

// `per_class` views of classes 0-2, in ten groups per class.
Eigen::MatrixXf Views(int per_class, uint64_t seed, std::vector<int>* groups = nullptr) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXf x(3 * per_class, kRaw);
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < per_class; ++i) {
      x.row(c * per_class + i) = View(c, rng).transpose();
      if (groups) groups->push_back(c * 10 + i % 10);
    }
  }
  return x;
}

Familiarity Fitted() {
  std::vector<int> groups;
  const Eigen::MatrixXf x = Views(60, 1, &groups);
  return Familiarity::Fit(x, groups);
}

TEST(Familiarity, RejectsAboutTheChosenShareOfViewsLikeTheTrainingOnes) {
  const Familiarity f = Fitted();
  EXPECT_EQ(f.reference.rows(), 180);
  EXPECT_EQ(f.held_out.size(), 180u);
  const Eigen::MatrixXf fresh = Views(200, 2);
  int below_5 = 0, below_50 = 0;
  for (Eigen::Index r = 0; r < fresh.rows(); ++r) {
    const double p = f.Of(fresh.row(r).transpose());
    EXPECT_GT(p, 0.0);
    EXPECT_LE(p, 1.0);
    below_5 += p < 0.05;
    below_50 += p < 0.5;
  }
  // About uniform: ~5 % below 0.05, ~50 % below 0.5 (600 fresh views; the bounds are wide for noise).
  EXPECT_GT(below_5, 600 * 0.01);
  EXPECT_LT(below_5, 600 * 0.12);
  EXPECT_GT(below_50, 600 * 0.35);
  EXPECT_LT(below_50, 600 * 0.65);
}

TEST(Familiarity, AViewOfAnotherColourOrShapeIsUnfamiliar) {
  const Familiarity f = Fitted();
  std::mt19937_64 rng(3);
  // A hue no class has, the rest like class 0: the hue block alone gives it away.
  Eigen::VectorXf other_hue = View(0, rng);
  other_hue.head(kHueBins).setZero();
  other_hue.segment(60, 10).setConstant(80);
  EXPECT_LT(f.Of(other_hue), 0.01);
  // Class 0's colours on a shape no class has.
  Eigen::VectorXf other_shape = View(0, rng);
  other_shape.tail(kCvfhBins).setConstant(0);
  other_shape.tail(kCvfhBins).head(20).setConstant(200);
  EXPECT_LT(f.Of(other_shape), 0.01);
  EXPECT_DOUBLE_EQ(f.Of(other_shape), 1.0 / (1 + f.held_out.size()));  // The smallest it can be.
}

TEST(Familiarity, AnObjectSeenFromNearerIsAsFamiliar) {
  const Familiarity f = Fitted();
  ASSERT_TRUE(f.colour_per_voxel);
  std::mt19937_64 rng(7);
  const Eigen::VectorXf far = View(1, rng);
  // Seen from 0.58 times the distance: three times the points, the same 5 mm voxels (CVFH's counts).
  Eigen::VectorXf near = far;
  near.head(kHsvBins) *= 3;
  EXPECT_GT(f.Of(far), 0.05);
  EXPECT_NEAR(f.Of(near), f.Of(far), 1e-9);
}

TEST(Familiarity, RefusesBadInput) {
  std::vector<int> groups;
  const Eigen::MatrixXf x = Views(10, 4, &groups);
  EXPECT_NE(ErrorOf([&] { Familiarity::Fit(x.leftCols(308), groups); }).find("raw parts"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { Familiarity::Fit(x, std::vector<int>(groups.size() - 1, 0)); }).find("groups"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { Familiarity::Fit(x, std::vector<int>(groups.size(), 7)); }).find("two groups"),
            std::string::npos);
  Eigen::MatrixXf negative = x;
  negative(3, 3) = -1;
  EXPECT_NE(ErrorOf([&] { Familiarity::Fit(negative, groups); }).find("negative or non-finite"), std::string::npos);
  // Past kMaxReference views the reference is a spread of them: a lone view of a second group left out of
  // it leaves no view a rival of another group (refused, not a scale of infinity).
  std::vector<int> lone(Familiarity::kMaxReference + 1, 0);
  lone.back() = 1;
  EXPECT_NE(ErrorOf([&] {
              Familiarity::Fit(Eigen::MatrixXf::Ones(static_cast<Eigen::Index>(lone.size()), 500), lone);
            }).find("another group"),
            std::string::npos);
  const Familiarity f = Familiarity::Fit(x, groups);
  EXPECT_NE(ErrorOf([&] { f.Of(Eigen::VectorXf::Zero(308)); }).find("expected 500 raw parts"), std::string::npos);
  EXPECT_DOUBLE_EQ(Familiarity{}.Of(x.row(0).transpose()), 1.0);  // Unfitted: everything familiar.
}

TEST(Familiarity, IsKeptInTheModelFileAndPartOfTheConfidence) {
  // A model over the three classes' views (raw parts as the 'color-cvfh' descriptor).
  std::vector<int> groups;
  const Eigen::MatrixXf x = Views(30, 5, &groups);
  std::vector<int> labels;
  for (int c = 0; c < 3; ++c) labels.insert(labels.end(), 30, c);
  SvmGrid grid;
  grid.C = {4};
  grid.gamma = {1.0 / 512};
  RecognitionModel m;
  m.descriptor = DescriptorKind::kColorCvfh;
  m.classes = {"red", "green", "blue"};
  m.classifier = SvmClassifier::Train(x, labels, groups, 3, grid);
  m.familiarity = Familiarity::Fit(x, groups);
  m.train_samples = 90;

  const std::filesystem::path file = std::filesystem::path(sortcell_test::TestTempDir()) / "familiar.model.json";
  SaveModel(file, m);
  const RecognitionModel loaded = LoadModel(file);
  ASSERT_FALSE(loaded.familiarity.empty());
  EXPECT_EQ(loaded.familiarity.held_out, m.familiarity.held_out);
  EXPECT_TRUE(loaded.familiarity.reference.isApprox(m.familiarity.reference));
  EXPECT_TRUE(loaded.familiarity.colour_per_voxel);
  // A model file of before has no colour_per_voxel: its reference holds colour per point and is read so.
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string key = "\"colour_per_voxel\": 1";
  ASSERT_NE(text.find(key), std::string::npos);
  auto load_with = [&](const std::string& replacement) {
    std::string edited = text;
    edited.replace(edited.find(key), key.size(), replacement);
    std::ofstream(file) << edited;
    return LoadModel(file);
  };
  EXPECT_FALSE(load_with("\"old_key\": 1").familiarity.colour_per_voxel);
  EXPECT_NE(ErrorOf([&] { load_with("\"colour_per_voxel\": 2"); }).find("'colour_per_voxel' is not 0 or 1"),
            std::string::npos);
  SaveModel(file, m);

  std::mt19937_64 rng(6);
  DescriptorParts parts;
  const Eigen::VectorXf view = View(1, rng);
  parts.hsv = view.head(kHsvBins);
  parts.cvfh = view.tail(kCvfhBins);
  const RecognitionModel::Result r = loaded.Classify(parts);
  EXPECT_EQ(r.name, "green");
  EXPECT_DOUBLE_EQ(r.familiarity, m.familiarity.Of(view));
  EXPECT_DOUBLE_EQ(r.confidence, r.probability * r.familiarity);
  parts.hsv.head(kHueBins).setZero();
  parts.hsv.segment(70, 10).setConstant(80);
  EXPECT_LT(loaded.Classify(parts).confidence, 0.01);  // Whatever the SVM's probability.
}

}  // namespace
}  // namespace sortcell::perception
