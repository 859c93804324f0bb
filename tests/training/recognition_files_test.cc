// Recognition files: a dataset round trip, every documented way LoadDataset rejects a damaged dataset
// (manifest.json and descriptors.csv missing, damaged or mistyped), EvaluateModel's checks, the report's
// CSV quoting and checked writes, and the spellings of grouping and split.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "files/object_set.h"
#include "training/dataset.h"
#include "training/default_model.h"
#include "training/recognition.h"
#include "error_of.h"
#include "source_tree.h"
#include "temp_dir.h"

namespace sortcell::training {
namespace {

using sortcell_test::ErrorOf;
using sortcell_test::TempDir;

Dataset SmallDataset() {
  Dataset d;
  d.object_set = "scenes/objects/test.yaml";
  d.views = 6;
  d.seed = 3;
  d.params.cvfh.min_points = 40;
  d.capture = {{"kind", "turntable"}};
  for (int i = 0; i < 3; ++i) {
    Sample s;
    s.id = 10 + i;
    s.category = i < 2 ? "bottle" : "cup";
    s.instance = i < 2 ? "bottle1" : "cup1";
    s.frame = i;
    s.cloud = "clouds/" + std::to_string(i) + ".pcd";
    s.points = 100 + i;
    s.purity = 0.5 + 0.1 * i;
    s.iou = 0.25;
    s.parts.hsv = Eigen::VectorXf::LinSpaced(perception::kHsvBins, 0.125f * i, 1.0f + i);
    s.parts.cvfh = Eigen::VectorXf::LinSpaced(perception::kCvfhBins, 1.0f / 3, 2.0f + i);
    s.parts.cvfh_regions = 1 + i;
    s.fits_familiarity = i != 1;
    d.samples.push_back(s);
  }
  return d;
}

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class DatasetFiles : public ::testing::Test {
 protected:
  void SetUp() override { SaveDataset(dir_.path(), SmallDataset()); }

  std::string Where() const { return "dataset '" + dir_.str() + "'"; }
  std::string Load() const {
    return ErrorOf([&] { LoadDataset(dir_.path()); });
  }
  nlohmann::json Manifest() const { return nlohmann::json::parse(ReadText(dir_ / "manifest.json")); }
  void WriteManifest(const nlohmann::json& m) const { std::ofstream(dir_ / "manifest.json") << m.dump(2); }
  std::vector<std::string> CsvLines() const {
    std::istringstream in(ReadText(dir_ / "descriptors.csv"));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
  void WriteCsv(const std::vector<std::string>& lines) const {
    std::ofstream out(dir_ / "descriptors.csv");
    for (const auto& line : lines) out << line << "\n";
  }

  TempDir dir_{"recognition_files"};
};

TEST_F(DatasetFiles, RoundTripKeepsSamplesPartsAndParameters) {
  const Dataset saved = SmallDataset();
  const Dataset loaded = LoadDataset(dir_.path());
  EXPECT_EQ(loaded.object_set, saved.object_set);
  EXPECT_EQ(loaded.views, 6);
  EXPECT_EQ(loaded.seed, 3u);
  EXPECT_TRUE(perception::SameDescriptorParams(loaded.params, saved.params));
  EXPECT_FALSE(perception::SameDescriptorParams(loaded.params, perception::DescriptorParams{}));
  EXPECT_EQ(loaded.capture, saved.capture);
  ASSERT_EQ(loaded.samples.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const Sample &a = saved.samples[i], &b = loaded.samples[i];
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.category, a.category);
    EXPECT_EQ(b.instance, a.instance);
    EXPECT_EQ(b.cloud, a.cloud);
    EXPECT_DOUBLE_EQ(b.purity, a.purity);
    EXPECT_EQ(b.parts.cvfh_regions, a.parts.cvfh_regions);
    EXPECT_EQ(b.fits_familiarity, a.fits_familiarity);
    EXPECT_EQ(b.parts.hsv, a.parts.hsv) << "9 digits round-trip a float";
    EXPECT_EQ(b.parts.cvfh, a.parts.cvfh);
  }
  EXPECT_EQ(loaded.Labels(perception::LabelKind::kCategory), (std::vector<std::string>{"bottle", "cup"}));
  EXPECT_EQ(loaded.Labels(perception::LabelKind::kInstance), (std::vector<std::string>{"bottle1", "cup1"}));
}

TEST_F(DatasetFiles, RejectsAMissingOrUnreadableManifest) {
  std::filesystem::remove(dir_ / "manifest.json");
  EXPECT_EQ(Load(), Where() + ": no manifest.json (make one with sortcell dataset)");
  std::ofstream(dir_ / "manifest.json") << "{\"format\": \"sortcell-dataset\", ";  // Truncated.
  EXPECT_EQ(Load(), Where() + ": manifest.json is not valid JSON");
  std::ofstream(dir_ / "manifest.json") << "[1, 2, 3]";
  EXPECT_EQ(Load(), Where() + ": manifest.json is not a SortCell dataset manifest");
}

TEST_F(DatasetFiles, RejectsAForeignManifestAndAnotherVersion) {
  nlohmann::json m = Manifest();
  m["format"] = "sortcell-recognition-model";
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json is not a SortCell dataset manifest");
  m = Manifest();
  m["format"] = "sortcell-dataset";
  m["version"] = 3;
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: format version 3, this build reads 1 to 2");
  m["version"] = 1;  // A manifest of before is read.
  WriteManifest(m);
  EXPECT_EQ(LoadDataset(dir_.path()).samples.size(), 3u);
}

TEST_F(DatasetFiles, RejectsMissingAndMistypedManifestKeys) {
  const nlohmann::json good = Manifest();
  nlohmann::json m = good;
  m.erase("object_set");
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: missing key 'object_set'");

  m = good;
  m["views"] = "many";
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: key 'views' is \"many\", expected an integer");

  m = good;
  m["seed"] = -1;
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: key 'seed' is -1, expected a non-negative integer");

  m = good;
  m["descriptor_params"]["cvfh_min_points"] = 2.5;  // Not silently truncated to 2.
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json descriptor_params: key 'cvfh_min_points' is 2.5, expected an integer");

  m = good;
  m["descriptor_params"].erase("cvfh_eps_angle_rad");
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json descriptor_params: missing key 'cvfh_eps_angle_rad'");

  m = good;
  m["samples"] = {{"id", 1}};
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: key 'samples' is not a list");
}

TEST_F(DatasetFiles, RejectsDamagedSamplesInTheManifest) {
  const nlohmann::json good = Manifest();
  nlohmann::json m = good;
  m["samples"][1]["category"] = 7;
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json samples[1]: key 'category' is 7, expected a string");

  m = good;
  m["samples"][2].erase("iou");
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json samples[2]: missing key 'iou'");

  m = good;
  m["samples"][0]["fits_familiarity"] = 1;
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json samples[0]: key 'fits_familiarity' is 1, expected true or false");

  m = good;
  m["samples"][1].erase("fits_familiarity");  // A manifest of before: every view fits the familiarity.
  WriteManifest(m);
  EXPECT_TRUE(LoadDataset(dir_.path()).samples[1].fits_familiarity);

  m = good;
  m["samples"][2]["id"] = m["samples"][0]["id"];
  WriteManifest(m);
  EXPECT_EQ(Load(), Where() + ": manifest.json: duplicate sample id 10");
}

TEST_F(DatasetFiles, RejectsAMissingOrDamagedDescriptorFile) {
  const std::vector<std::string> good = CsvLines();
  ASSERT_EQ(good.size(), 4u) << "header and three samples";
  const std::string csv = Where() + ": descriptors.csv";

  std::filesystem::remove(dir_ / "descriptors.csv");
  EXPECT_EQ(Load(), Where() + ": no descriptors.csv");

  std::vector<std::string> lines = good;
  lines[2].replace(lines[2].find(','), 1, ",abc,");
  WriteCsv(lines);
  EXPECT_EQ(Load(), csv + ": row 3 holds a non-number");

  lines = good;
  lines[1].replace(lines[1].find(','), 1, ";");
  WriteCsv(lines);
  EXPECT_EQ(Load(), csv + ": row 2 is malformed");

  lines = good;
  lines[3] = lines[3].substr(0, lines[3].rfind(','));  // One column short.
  WriteCsv(lines);
  EXPECT_EQ(Load(), csv + ": row 4 has 500 columns, expected 501");

  lines = good;
  lines[1].replace(0, lines[1].find(','), "99");
  WriteCsv(lines);
  EXPECT_EQ(Load(), csv + ": row 2 names an unknown sample");

  lines = good;
  lines.pop_back();
  WriteCsv(lines);
  EXPECT_EQ(Load(), csv + ": no descriptor for sample 12");
}

// A CVFH model of the dataset's categories (trained on the dataset's own CVFH descriptors, repeated).
perception::RecognitionModel ModelFor(const Dataset& d) {
  perception::RecognitionModel model;
  model.descriptor = perception::DescriptorKind::kCvfh;
  model.params = d.params;
  model.classes = {"bottle", "cup"};
  Eigen::MatrixXf x(12, perception::kCvfhBins);
  std::vector<int> labels, groups;
  for (int r = 0; r < 12; ++r) {
    const Sample& s = d.samples[r % 3];
    x.row(r) = perception::AssembleDescriptor(s.parts, model.descriptor).transpose();
    labels.push_back(s.category == "bottle" ? 0 : 1);
    groups.push_back(r % 4);
  }
  perception::SvmGrid grid;
  grid.C = {1};
  grid.gamma = {1.0 / perception::kCvfhBins};
  grid.threads = 1;
  model.classifier = perception::SvmClassifier::Train(x, labels, groups, 2, grid);
  return model;
}

TEST(EvaluateModel, ClassifiesTheDatasetWithAModelOfItsParameters) {
  const Dataset d = SmallDataset();
  const Evaluation e = EvaluateModel(ModelFor(d), d, {}, "scenes");
  EXPECT_EQ(e.test_samples, 3);
  EXPECT_EQ(e.confusion.counts().sum(), 3);
}

TEST(EvaluateModel, RejectsADatasetDescribedWithOtherParameters) {
  const Dataset d = SmallDataset();
  perception::RecognitionModel model = ModelFor(d);
  model.params.cvfh.min_points = 30;
  model.params.hsv.min_value = 20;
  EXPECT_EQ(ErrorOf([&] { EvaluateModel(model, d, {}, "scenes"); }),
            "dataset 'scenes': its descriptors were computed with other parameters than the model's "
            "(hsv_min_value: dataset 26, model 20; cvfh_min_points: dataset 40, model 30)");
}

TEST(EvaluateModel, RejectsASampleOfAClassTheModelDoesNotKnow) {
  const Dataset d = SmallDataset();
  perception::RecognitionModel model = ModelFor(d);
  model.classes = {"bottle"};
  const std::vector<int> cup_row = {2};  // Checked before anything is classified.
  EXPECT_EQ(ErrorOf([&] { EvaluateModel(model, d, cup_row, "scenes"); }),
            "dataset 'scenes': sample 12 is a 'cup', not one of the model's category classes");
  model.label_kind = perception::LabelKind::kInstance;
  model.classes = {"bottle1"};
  EXPECT_EQ(ErrorOf([&] { EvaluateModel(model, d, cup_row, "scenes"); }),
            "dataset 'scenes': sample 12 is a 'cup1', not one of the model's instance classes");
}

// Classes whose names need quoting in CSV: a comma, a double quote.
Evaluation EvaluationWithAwkwardNames() {
  Evaluation e{perception::DescriptorKind::kCvfh,
               perception::ConfusionMatrix({"apple, red", "say \"cheese\""}),
               {},
               1,
               0.5,
               0.75,
               10,
               4,
               0.5};
  e.confusion.Add(0, 0, 2);
  e.confusion.Add(1, 0);
  e.confusion.Add(1, 1);
  e.metrics = perception::ComputeMetrics(e.confusion);
  return e;
}

TEST(RecognitionReport, QuotesCsvFields) {
  const TempDir dir("recognition_report");
  const std::string markdown = WriteRecognitionReport(dir.path(), "Awkward names", {EvaluationWithAwkwardNames()});
  EXPECT_EQ(ReadText(dir / "tables.md"), markdown);
  const std::string metrics = ReadText(dir / "metrics.csv");
  EXPECT_NE(metrics.find("\ncvfh,\"apple, red\",1,"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\ncvfh,\"say \"\"cheese\"\"\",0.5,"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\ncvfh,macro,"), std::string::npos) << metrics;
  EXPECT_EQ(ReadText(dir / "confusion_cvfh.csv"),
            "actual\\predicted,\"apple, red\",\"say \"\"cheese\"\"\"\n"
            "\"apple, red\",100.0000,0.0000\n"
            "\"say \"\"cheese\"\"\",50.0000,50.0000\n");
  EXPECT_TRUE(std::filesystem::exists(dir / "confusion_cvfh.png"));
}

TEST(RecognitionReport, AFailedWriteIsAnErrorNamingTheFile) {
  const TempDir dir("recognition_report");
  const std::filesystem::path gone = dir / "no_such_folder";
  try {
    WriteRecognitionReport(gone, "Nowhere", {EvaluationWithAwkwardNames()});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '" + (gone / "confusion_cvfh.csv").string() + "'"),
              std::string::npos)
        << e.what();
  }
}

// Scene views of two colours in eight scenes; the views of scenes 4-7 (`widened` of them) are
// classifier-only and far brighter than the rest.
Dataset WidenedScenes(bool widened) {
  Dataset d;
  d.capture = {{"kind", "scenes"}};
  for (int i = 0; i < 32; ++i) {
    Sample s;
    s.id = i;
    s.scene = i / 4;
    s.category = i % 2 == 0 ? "red" : "blue";
    s.instance = s.category + "1";
    s.source = "scene";
    const bool bright = s.scene >= 4;
    s.fits_familiarity = !(bright && widened);
    s.parts.hsv = Eigen::VectorXf::Constant(perception::kHsvBins, 1.0f + 0.01f * static_cast<float>(i));
    s.parts.hsv.segment(i % 2 == 0 ? 0 : 40, 10).setConstant(bright ? 400.0f : 40.0f);
    s.parts.cvfh = Eigen::VectorXf::Constant(perception::kCvfhBins, 5.0f + 0.01f * static_cast<float>(i % 5));
    d.samples.push_back(s);
  }
  return d;
}

TEST(TrainModel, OnlyTheViewsThatFitTheFamiliarityFitIt) {
  TrainRequest request;
  request.grid.C = {4};
  request.grid.gamma = {1.0 / 8};
  request.grid.threads = 1;
  const perception::RecognitionModel all = TrainModel(WidenedScenes(false), {}, request);
  const perception::RecognitionModel some = TrainModel(WidenedScenes(true), {}, request);
  EXPECT_EQ(all.train_samples, 32);
  EXPECT_EQ(some.train_samples, 32) << "the classifier learns from every view";
  EXPECT_EQ(all.familiarity.held_out.size(), 32u);
  EXPECT_EQ(some.familiarity.held_out.size(), 16u);
  // A bright view like those of scenes 4-7 (not one of them) is familiar where they fitted the familiarity,
  // unfamiliar where they did not.
  const Dataset widened = WidenedScenes(true);
  Sample bright = widened.samples[20];
  bright.parts.hsv.array() += 0.005f;
  bright.parts.cvfh.array() += 0.02f;
  EXPECT_GT(all.familiarity.Of(perception::RawParts(bright.parts)), 0.05);
  EXPECT_LT(some.familiarity.Of(perception::RawParts(bright.parts)), 0.07);
  Dataset none = widened;
  for (Sample& s : none.samples) s.fits_familiarity = false;
  EXPECT_EQ(ErrorOf([&] { TrainModel(none, {}, request); }),
            "training: none of the 32 samples trained on fits the familiarity (all were captured with "
            "--classifier-only): train them together with views captured without it");
}

// `train --if-stale` and the model cache judge a recipe's model by its digest: current only beside the
// digest of the same set and recipe (and scene count); a model without one (or with another) is stale, and a model
// written by other means forgets it.
TEST(DefaultModelDigest, OnlyTheSameSetsDigestIsCurrent) {
  const TempDir dir("model_digest");
  const files::ObjectSet paper = files::LoadObjectSet(sortcell_test::kRoot / "scenes/objects/paper.yaml");
  const files::ObjectSet produce = files::LoadObjectSet(sortcell_test::kRoot / "scenes/objects/produce.yaml");
  const std::filesystem::path model = dir / "paper.model.json";
  EXPECT_FALSE(TrainedOnIsCurrent(paper, model)) << "no model";
  std::ofstream(model) << "{}";
  EXPECT_FALSE(TrainedOnIsCurrent(paper, model)) << "no digest";
  RecordTrainedOn(paper, model);
  EXPECT_TRUE(TrainedOnIsCurrent(paper, model));
  EXPECT_FALSE(TrainedOnIsCurrent(produce, model)) << "another set's digest";
  EXPECT_FALSE(TrainedOnIsCurrent(paper, model, 20)) << "another scene count (train --scenes 20)";
  RecordTrainedOn(paper, model, 20);
  EXPECT_TRUE(TrainedOnIsCurrent(paper, model, 20));
  EXPECT_FALSE(TrainedOnIsCurrent(paper, model)) << "a quick model is not the cache's default";
  std::ofstream(model.string() + ".trained_on") << "model of an older recipe\n";
  EXPECT_FALSE(TrainedOnIsCurrent(paper, model));
  ForgetTrainedOn(model);
  EXPECT_FALSE(std::filesystem::exists(model.string() + ".trained_on"));
  ForgetTrainedOn(model);  // Nothing to forget: no error.
  EXPECT_EQ(ErrorOf([&] { RecordTrainedOn(paper, model, 0); }), "the recipe's scene count must be 1 or more (got 0)");
}

TEST(RecognitionSpellings, GroupingAndSplitRoundTripAndUnknownOnesAreClearErrors) {
  for (Grouping g : {Grouping::kSequence, Grouping::kInstance}) EXPECT_EQ(ParseGrouping(ToString(g)), g);
  for (ExperimentSplit s : {ExperimentSplit::kPaper, ExperimentSplit::kUnseenInstance}) {
    EXPECT_EQ(ParseExperimentSplit(ToString(s)), s);
  }
  EXPECT_STREQ(ToString(ExperimentSplit::kUnseenInstance), "unseen-instance");
  EXPECT_EQ(ErrorOf([] { ParseGrouping("frame"); }), "unknown grouping 'frame' (expected sequence or instance)");
  EXPECT_EQ(ErrorOf([] { ParseExperimentSplit("random"); }),
            "unknown split 'random' (expected paper or unseen-instance)");
}

}  // namespace
}  // namespace sortcell::training
