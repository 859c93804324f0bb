#include "training/experiment.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "files/data_dir.h"
#include "files/object_set.h"
#include "files/output_dir.h"
#include "files/progress.h"
#include "common/seeding.h"
#include "common/wall_clock.h"
#include "training/dataset_capture.h"
#include "training/experiment_splits.h"
#include "training/recognition.h"
#include "sim/kinect_colour.h"
#include "sim/kinect_noise.h"

namespace sortcell::training {
namespace {

using perception::DescriptorKind;

files::ObjectSet Set(const std::string& name) {
  return files::LoadObjectSet(std::filesystem::path(files::DataDir()) / "scenes" / "objects" / (name + ".yaml"));
}

// The dataset in `dir` if it was made from `set` with these settings, else a fresh capture.
template <typename Capture>
Dataset ReuseOrCapture(const std::filesystem::path& dir, const files::ObjectSet& set, int views, uint64_t seed,
                       nlohmann::json capture_settings, Capture capture) {
  capture_settings["object_models"] = files::ObjectModelsDigest(set, files::ObjectTexturesDir());
  // The sensor's colour and depth models too: data rendered through others is not this capture.
  capture_settings["kinect_colour"] = sim::ToString(sim::KinectColourParams{});
  capture_settings["kinect_depth"] = sim::ToString(sim::KinectNoiseParams{});
  try {
    Dataset d = LoadDataset(dir);
    if (d.object_set == set.source.string() && d.views == views && d.seed == seed &&
        d.capture.value("settings", nlohmann::json()) == capture_settings &&
        perception::SameDescriptorParams(d.params, perception::DescriptorParams{})) {
      spdlog::info("reusing the dataset in {} ({} samples)", dir.string(), d.samples.size());
      return d;
    }
    spdlog::info("the dataset in {} was made with other settings: capturing it again", dir.string());
  } catch (const std::invalid_argument&) {
    // No dataset there yet (or a damaged one): capture it.
  }
  std::filesystem::remove_all(dir);
  Dataset d = capture(dir);
  d.capture["settings"] = capture_settings;
  SaveDataset(dir, d);
  return d;
}

// Experiment 3's data: turntable views of the paper objects to train, random cell scenes to test.
Trial SceneTrial(const Dataset& train_data, const Dataset& scene_data, int scenes) {
  Trial t;
  for (size_t i = 0; i < train_data.samples.size(); ++i) t.train.push_back(static_cast<int>(i));
  for (size_t i = 0; i < scene_data.samples.size(); ++i) t.test.push_back(static_cast<int>(i));
  t.description = {{"train", "turntable views of the six paper objects"},
                   {"test", "objects segmented from " + std::to_string(scenes) + " random cell scenes"},
                   {"scene_capture", scene_data.capture}};
  return t;
}

// A dataset made elsewhere (e.g. `dataset --from-rgbd-objects`) when `dir` holds one, else none.
std::optional<Dataset> GivenDataset(const std::filesystem::path& dir) {
  if (dir.empty() || !std::filesystem::exists(dir / "manifest.json")) return std::nullopt;
  return LoadDataset(dir);
}

// One descriptor trained and evaluated on every trial.
struct DescriptorRun {
  std::vector<Evaluation> trials;
  Evaluation pooled;
  double train_wall_s = 0;
};

DescriptorRun RunDescriptor(DescriptorKind kind, const Dataset& train_data, const Dataset& test_data,
                            const std::vector<Trial>& trials, const std::filesystem::path& out,
                            files::Progress& progress) {
  std::vector<Evaluation> evaluations;
  double train_wall_s = 0;
  for (const Trial& trial : trials) {
    TrainRequest request = trial.request;
    request.descriptor = kind;
    const auto train_start = WallClock::now();
    const perception::RecognitionModel model = TrainModel(train_data, trial.train, request);
    train_wall_s += SecondsSince(train_start);
    // One model per descriptor where there is one trial; a trial's model has not seen some instances,
    // so those of several trials are not kept.
    if (trials.size() == 1) {
      perception::SaveModel(out / "models" / (perception::DescriptorName(kind) + ".model.json"), model);
    }
    evaluations.push_back(EvaluateModel(model, test_data, trial.test, "experiment data"));
    progress.Advance();
  }
  Evaluation pooled = PoolEvaluations(evaluations);
  return {std::move(evaluations), std::move(pooled), train_wall_s};
}

// results.json's entry for one descriptor. Several trials: "macro_f1" is their mean, beside its
// spread and each trial's; the other figures are of the pooled confusion matrix.
nlohmann::json DescriptorJson(const DescriptorRun& run) {
  nlohmann::json j = EvaluationJson(run.pooled);
  j["train_wall_s"] = run.train_wall_s;
  if (run.trials.size() < 2) return j;
  std::vector<double> f1;
  nlohmann::json trials = nlohmann::json::array();
  for (const Evaluation& e : run.trials) {
    f1.push_back(e.metrics.macro_f1);
    trials.push_back({{"macro_f1", e.metrics.macro_f1},
                      {"accuracy", e.metrics.accuracy},
                      {"svm", {{"C", e.C}, {"gamma", e.gamma}, {"cv_accuracy", e.cv_accuracy}}}});
  }
  const double mean = std::accumulate(f1.begin(), f1.end(), 0.0) / f1.size();
  double variance = 0;
  for (double x : f1) variance += (x - mean) * (x - mean) / (f1.size() - 1);
  j["macro_f1_pooled"] = j["macro_f1"];
  j["macro_f1"] = mean;
  j["macro_f1_std"] = std::sqrt(variance);
  j["macro_f1_min"] = *std::min_element(f1.begin(), f1.end());
  j["macro_f1_max"] = *std::max_element(f1.begin(), f1.end());
  j["trials"] = trials;
  return j;
}

// The table of trials: what each held out and each descriptor's macro F1; mean, spread and range.
std::string TrialTable(const std::vector<Trial>& trials, const std::vector<DescriptorRun>& runs) {
  std::string table = "### Trials: one instance of every category held out in each\n\n| trial | held out |";
  std::string rule = "|---|---|";
  for (const auto& run : runs) {
    table += " " + perception::DescriptorTitle(run.pooled.descriptor) + " macro F1 |";
    rule += "---:|";
  }
  table += "\n" + rule + "\n";
  for (size_t t = 0; t < trials.size(); ++t) {
    std::string held_out;
    for (const auto& [category, instance] : trials[t].description["test_instances"].items()) {
      held_out += (held_out.empty() ? "" : ", ") + instance.get<std::string>();
    }
    table += fmt::format("| {} | {} |", t + 1, held_out);
    for (const auto& run : runs) table += fmt::format(" {:.4f} |", run.trials[t].metrics.macro_f1);
    table += "\n";
  }
  table += "| **mean ± std** | |";
  for (const auto& run : runs) {
    const nlohmann::json j = DescriptorJson(run);
    table += fmt::format(" **{:.4f}** ± {:.4f} |", j["macro_f1"].get<double>(), j["macro_f1_std"].get<double>());
  }
  table += "\n| min-max | |";
  for (const auto& run : runs) {
    const nlohmann::json j = DescriptorJson(run);
    table += fmt::format(" {:.4f}-{:.4f} |", j["macro_f1_min"].get<double>(), j["macro_f1_max"].get<double>());
  }
  return table + "\n\nThe tables below pool the trials' test views into one confusion matrix.\n";
}

// Refuses options the experiment does not have.
void CheckExperimentOptions(const ExperimentOptions& options) {
  if (options.number < 1 || options.number > 3) {
    throw std::invalid_argument("unknown experiment " + std::to_string(options.number) + " (expected 1, 2 or 3)");
  }
  if (options.number != 1 && options.split != ExperimentSplit::kPaper) {
    throw std::invalid_argument("--split: experiment " + std::to_string(options.number) + " has only the paper split");
  }
  if (options.trials != 0 && options.split != ExperimentSplit::kUnseenInstance) {
    throw std::invalid_argument("--trials: only the unseen-instance split has trials");
  }
}

// The experiment's data and its trials.
struct ExperimentData {
  Dataset train, scenes;
  std::vector<Trial> trials;
  const Dataset& test(int number) const { return number == 3 ? scenes : train; }
};

// Captures (or reuses) the turntable views of `set` into data/<set>_turntable.
Dataset Turntable(const ExperimentOptions& options, const std::filesystem::path& data, const files::ObjectSet& set) {
  // Experiment 3 tests on segments of cluttered scenes, where nearer objects hide parts of farther ones:
  // its training views get an occluded copy each (TurntableOptions::occluded_copies).
  const int occluded_copies = options.number == 3 ? 1 : 0;
  nlohmann::json settings = {{"kind", "turntable"}, {"views", options.views}};
  if (occluded_copies > 0) settings["occluded_copies"] = occluded_copies;
  return ReuseOrCapture(data / (set.name + "_turntable"), set, options.views, options.seed, settings,
                        [&](const std::filesystem::path& dir) {
                          TurntableOptions t;
                          t.views = options.views;
                          t.seed = options.seed;
                          t.occluded_copies = occluded_copies;
                          return CaptureTurntable(set, t, dir);
                        });
}

ExperimentData PrepareData(const ExperimentOptions& options, const std::filesystem::path& data,
                           const std::optional<Dataset>& given) {
  ExperimentData d;
  if (options.number == 1 || options.number == 2) {
    d.train = given ? *given : Turntable(options, data, Set("produce"));
    if (options.number == 2) {
      d.trials = {SequenceSplit(d.train, options.seed)};
    } else if (options.split == ExperimentSplit::kPaper) {
      d.trials = {FrameSplit(d.train)};
    } else {
      d.trials = LeaveOneInstanceOutTrials(d.train, options.trials, options.seed);
    }
    return d;
  }
  const files::ObjectSet paper = Set("paper");
  d.train = Turntable(options, data, paper);
  d.scenes = ReuseOrCapture(data / "paper_scenes", paper, 0, options.seed,
                            {{"kind", "scenes"}, {"scenes", options.scenes}}, [&](const std::filesystem::path& dir) {
                              SceneOptions s;
                              s.scenes = options.scenes;
                              s.seed = options.seed;
                              // The paper's pipeline: its segmentation is Euclidean clustering (the
                              // cell now segments with convex clusters; the experiments reproduce the paper).
                              s.clustering = perception::SegmentationParams::Clustering::kEuclidean;
                              return CaptureScenes(paper, s, dir);
                            });
  d.trials = {SceneTrial(d.train, d.scenes, options.scenes)};
  return d;
}

// results.json: the split, the samples per trial (the first's: the trials differ by a few views), and
// each descriptor's figures.
nlohmann::json ResultsJson(const ExperimentOptions& options, const std::optional<Dataset>& given,
                           const std::vector<Trial>& trials, const nlohmann::json& descriptors) {
  nlohmann::json split_detail = trials.front().description;
  if (trials.size() > 1) {
    split_detail = nlohmann::json::array();
    for (const Trial& t : trials) split_detail.push_back(t.description);
  }
  nlohmann::json results = {{"experiment", options.number},
                            {"split", ToString(options.split)},
                            {"views", given ? given->views : options.views},
                            {"seed", options.seed},
                            {"trials", trials.size()},
                            {"train_samples", trials.front().train.size()},
                            {"test_samples", trials.front().test.size()},
                            {"split_detail", split_detail},
                            {"descriptors", descriptors}};
  if (given) results["data"] = options.data.string();
  return results;
}

}  // namespace

nlohmann::json RunExperiment(const ExperimentOptions& options, const std::vector<std::string>& command_line) {
  CheckExperimentOptions(options);
  const std::optional<Dataset> given = GivenDataset(options.data);
  if (given && options.number == 3) {
    throw std::invalid_argument(
        "--data '" + options.data.string() +
        "' holds one dataset; experiment 3 needs a folder for its turntable and scene datasets");
  }
  const auto start = WallClock::now();
  files::PrepareOutputDir(options.out);
  const ExperimentData data = PrepareData(options, options.data.empty() ? options.out / "data" : options.data, given);
  const std::vector<Trial>& trials = data.trials;

  std::filesystem::create_directories(options.out / "models");
  std::vector<DescriptorRun> runs;
  nlohmann::json descriptors = nlohmann::json::object();
  files::Progress progress("experiment " + std::to_string(options.number) + " training",
                           3 * static_cast<int>(trials.size()));
  for (DescriptorKind kind : {DescriptorKind::kCvfh, DescriptorKind::kColorCvfh, DescriptorKind::kColorCvfhNorm}) {
    runs.push_back(RunDescriptor(kind, data.train, data.test(options.number), trials, options.out, progress));
    descriptors[perception::DescriptorName(kind)] = DescriptorJson(runs.back());
  }
  progress.Finish();
  std::vector<Evaluation> pooled;
  for (const auto& run : runs) pooled.push_back(run.pooled);
  const std::string title = fmt::format("Experiment {} (split {}, {} views per revolution, seed {}{})", options.number,
                                        ToString(options.split), given ? given->views : options.views, options.seed,
                                        trials.size() > 1 ? fmt::format(", {} trials", trials.size()) : "");
  WriteRecognitionReport(options.out, title, pooled, trials.size() > 1 ? TrialTable(trials, runs) : "");
  const nlohmann::json results = ResultsJson(options, given, trials, descriptors);
  files::WriteJson(options.out / "results.json", results);
  files::WriteJson(options.out / "run.json",
                   files::RunRecord(command_line, options.seed,
                                    {{"command", "experiment"}, {"experiment_wall_s", SecondsSince(start)}}));
  return results;
}

}  // namespace sortcell::training
