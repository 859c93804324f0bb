#include "app/cli/experiment_command.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <random>
#include <set>

#include "app/cli/cli_validators.h"
#include "app/recognition/dataset_capture.h"
#include "app/common/object_set.h"
#include "app/common/data_dir.h"
#include "app/common/output_dir.h"
#include "app/common/progress.h"
#include "app/recognition/recognition.h"
#include "app/common/seeding.h"
#include "app/common/wall_clock.h"

namespace sortcell::app {
namespace {

using perception::DescriptorKind;

ObjectSet Set(const std::string& name) {
  return LoadObjectSet(std::filesystem::path(DataDir()) / "scenes" / "objects" / (name + ".yaml"));
}

// The dataset in `dir` if it was made from `set` with these settings, else a fresh capture.
template <typename Capture>
Dataset ReuseOrCapture(const std::filesystem::path& dir, const ObjectSet& set, int views, uint64_t seed,
                       const nlohmann::json& capture_settings, Capture capture) {
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

struct Split {
  std::vector<int> train, test;
  TrainRequest request;
  nlohmann::json description;
};

Split FrameSplit(const Dataset& d) {
  Split s;
  for (size_t i = 0; i < d.samples.size(); ++i) (d.samples[i].frame % 4 == 3 ? s.test : s.train).push_back(static_cast<int>(i));
  s.description = {{"test", "every fourth view (frame % 4 == 3) of every turntable sequence"}};
  return s;
}

Split UnseenInstanceSplit(const Dataset& d, uint64_t seed) {
  std::map<std::string, std::set<std::string>> instances;
  for (const auto& sample : d.samples) instances[sample.category].insert(sample.instance);
  std::mt19937_64 rng = EpisodeRng(seed, 0x5911);
  std::set<std::string> held_out;
  nlohmann::json test_instances = nlohmann::json::object();
  for (const auto& [category, names] : instances) {
    if (names.size() < 2) throw std::invalid_argument("unseen-instance split: category '" + category + "' has one instance");
    std::vector<std::string> v(names.begin(), names.end());
    const std::string pick = v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
    held_out.insert(pick);
    test_instances[category] = pick;
  }
  Split s;
  for (size_t i = 0; i < d.samples.size(); ++i) {
    (held_out.count(d.samples[i].instance) ? s.test : s.train).push_back(static_cast<int>(i));
  }
  s.request.group_by = Grouping::kInstance;
  s.description = {{"test_instances", test_instances}};
  return s;
}

Split SequenceSplit(const Dataset& d, uint64_t seed) {
  // Sequences: (instance, elevation, third of the revolution); nine per instance.
  std::map<std::string, std::set<std::pair<double, int>>> sequences;
  auto part = [&](const Sample& s) { return 3 * s.frame / std::max(1, d.views); };
  for (const auto& s : d.samples) {
    if (s.category == "apple" || s.category == "orange") sequences[s.instance].insert({s.elevation_deg, part(s)});
  }
  std::mt19937_64 rng = EpisodeRng(seed, 0x5e9);
  std::map<std::string, std::set<std::pair<double, int>>> test;
  nlohmann::json chosen = nlohmann::json::object();
  for (const auto& [instance, seqs] : sequences) {
    std::vector<std::pair<double, int>> v(seqs.begin(), seqs.end());
    std::shuffle(v.begin(), v.end(), rng);
    for (size_t k = 0; k < std::min<size_t>(2, v.size()); ++k) {
      test[instance].insert(v[k]);
      chosen[instance].push_back({{"elevation_deg", v[k].first}, {"part", v[k].second}});
    }
  }
  Split s;
  for (size_t i = 0; i < d.samples.size(); ++i) {
    const Sample& x = d.samples[i];
    if (!sequences.count(x.instance)) continue;
    (test[x.instance].count({x.elevation_deg, part(x)}) ? s.test : s.train).push_back(static_cast<int>(i));
  }
  s.request.label_kind = perception::LabelKind::kInstance;
  s.description = {{"test_sequences", chosen}, {"sequences_per_instance", 9}};
  return s;
}

}  // namespace

nlohmann::json RunExperiment(const ExperimentOptions& options, const std::vector<std::string>& command_line) {
  if (options.number < 1 || options.number > 3) {
    throw std::invalid_argument("unknown experiment " + std::to_string(options.number) + " (expected 1, 2 or 3)");
  }
  if (options.number != 1 && options.split != ExperimentSplit::kPaper) {
    throw std::invalid_argument("--split: experiment " + std::to_string(options.number) + " has only the paper split");
  }
  const auto start = WallClock::now();
  PrepareOutputDir(options.out);
  const std::filesystem::path data = options.data.empty() ? options.out / "data" : options.data;
  const nlohmann::json turntable_settings = {{"kind", "turntable"}, {"views", options.views}};

  auto turntable = [&](const ObjectSet& set) {
    return ReuseOrCapture(data / (set.name + "_turntable"), set, options.views, options.seed, turntable_settings,
                          [&](const std::filesystem::path& dir) {
                            TurntableOptions t;
                            t.views = options.views;
                            t.seed = options.seed;
                            return CaptureTurntable(set, t, dir);
                          });
  };

  Dataset train_data, scene_data;
  Split split;
  if (options.number == 1 || options.number == 2) {
    train_data = turntable(Set("produce"));
    split = options.number == 2 ? SequenceSplit(train_data, options.seed)
            : options.split == ExperimentSplit::kPaper ? FrameSplit(train_data)
                                                       : UnseenInstanceSplit(train_data, options.seed);
  } else {
    const ObjectSet paper = Set("paper");
    train_data = turntable(paper);
    scene_data = ReuseOrCapture(data / "paper_scenes", paper, 0, options.seed,
                                {{"kind", "scenes"}, {"scenes", options.scenes}}, [&](const std::filesystem::path& dir) {
                                  SceneOptions s;
                                  s.scenes = options.scenes;
                                  s.seed = options.seed;
                                  return CaptureScenes(paper, s, dir);
                                });
    for (size_t i = 0; i < train_data.samples.size(); ++i) split.train.push_back(static_cast<int>(i));
    for (size_t i = 0; i < scene_data.samples.size(); ++i) split.test.push_back(static_cast<int>(i));
    split.description = {{"train", "turntable views of the six paper objects"},
                         {"test", "objects segmented from " + std::to_string(options.scenes) + " random cell scenes"},
                         {"scene_capture", scene_data.capture}};
  }
  const Dataset& test_data = options.number == 3 ? scene_data : train_data;

  std::filesystem::create_directories(options.out / "models");
  std::vector<Evaluation> evaluations;
  nlohmann::json descriptors = nlohmann::json::object();
  Progress progress("experiment " + std::to_string(options.number) + " training", 3);
  for (DescriptorKind kind : {DescriptorKind::kCvfh, DescriptorKind::kColorCvfh, DescriptorKind::kColorCvfhNorm}) {
    TrainRequest request = split.request;
    request.descriptor = kind;
    const auto train_start = WallClock::now();
    const perception::RecognitionModel model = TrainModel(train_data, split.train, request);
    const double train_s = SecondsSince(train_start);
    perception::SaveModel(options.out / "models" / (perception::DescriptorName(kind) + ".model.json"), model);
    evaluations.push_back(EvaluateModel(model, test_data, split.test, "experiment data"));
    descriptors[perception::DescriptorName(kind)] = EvaluationJson(evaluations.back());
    descriptors[perception::DescriptorName(kind)]["train_wall_s"] = train_s;
    progress.Advance();
  }
  progress.Finish();
  const std::string title = fmt::format("Experiment {} (split {}, {} views per revolution, seed {})", options.number,
                                        ToString(options.split), options.views, options.seed);
  WriteRecognitionReport(options.out, title, evaluations);
  nlohmann::json results = {{"experiment", options.number}, {"split", ToString(options.split)},
                            {"views", options.views}, {"seed", options.seed}, {"train_samples", split.train.size()},
                            {"test_samples", split.test.size()}, {"split_detail", split.description},
                            {"descriptors", descriptors}};
  WriteJson(options.out / "results.json", results);
  WriteJson(options.out / "run.json", RunRecord(command_line, options.seed, {{"command", "experiment"},
                                                                          {"experiment_wall_s", SecondsSince(start)}}));
  return results;
}

void AddExperimentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<ExperimentOptions>();
  auto split = std::make_shared<std::string>(ToString(o->split));
  CLI::App* cmd = app.add_subcommand(
      "experiment",
      "Run one of the paper's recognition experiments whole (section 3, Tables 1-8): 1 = category level on the "
      "produce set, 2 = instance level on apple1-5 and orange1-4, 3 = the six paper objects tested in random cell "
      "scenes. Captures the data into DIR/data (reused when it matches), trains and evaluates CVFH, Color-CVFH and "
      "Color-CVFH (normalization), and writes tables.md, metrics.csv, confusion_*.csv/.png, results.json, models/.");
  cmd->add_option("experiment", o->number, "1, 2 or 3")->required()->check(CLI::IsMember({1, 2, 3}));
  cmd->add_option("--split", *split, "paper | unseen-instance (experiment 1 only)")->capture_default_str();
  cmd->add_option("--views", o->views, "Turntable views per revolution and elevation")
      ->check(CLI::Range(3, 3600))->capture_default_str();
  cmd->add_option("--scenes", o->scenes, "Experiment 3: random cell scenes to test on")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed (uint64)")->check(kUnsignedInteger)->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder (created if missing)")->required();
  cmd->add_option("--data", o->data,
                  "Folder of the captured datasets, reused when they match (default DIR/data); experiments 1 "
                  "and 2 share the produce turntable data");
  cmd->callback([&run, o, split, command_line] {
    run = [o, split, command_line] {
      o->split = ParseOption("--split", *split, ParseExperimentSplit);
      const nlohmann::json r = RunExperiment(*o, command_line);
      std::cout << "Experiment " << o->number << " (" << ToString(o->split) << "): " << r["train_samples"]
                << " training, " << r["test_samples"] << " test samples. Macro F1:";
      for (const auto& [name, d] : r["descriptors"].items()) std::cout << " " << name << " " << d["macro_f1"].get<double>();
      std::cout << ". Tables in " << o->out.string() << "/tables.md\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
