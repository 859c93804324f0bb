#include "app/cli/recognition_commands.h"

#include <spdlog/fmt/fmt.h>

#include <fstream>
#include <iostream>
#include <memory>

#include "app/cli/cli_validators.h"
#include "training/dataset_capture.h"
#include "training/default_model.h"
#include "files/object_set.h"
#include "files/output_dir.h"
#include "training/out_of_set.h"
#include "training/recognition.h"
#include "training/rgbd_objects.h"
#include "common/wall_clock.h"

namespace sortcell::app {
namespace {

struct DatasetOptions {
  std::filesystem::path objects, rgbd_objects, out;
  int views = 36;
  int scenes = 0;
  int occluded = 0;
  uint64_t seed = 0;
  std::vector<std::string> placement{"sparse"};
  double lying_fraction = 0;
  double colour_jitter = 0;
  double depth_noise_max = 1;
  bool classifier_only = false;
};

struct TrainOptions {
  std::filesystem::path dataset, objects, out;
  std::string descriptor = perception::DescriptorName(perception::DescriptorKind::kColorCvfhNorm);
  std::string label = perception::ToString(perception::LabelKind::kCategory);
  std::string group_by = ToString(training::Grouping::kSequence);
  int scenes = training::kDefaultRecipeScenes;
  bool if_stale = false;
};

struct EvalOptions {
  std::filesystem::path dataset, model, out;
};

// `sortcell dataset --from-rgbd-objects DIR --out OUT`.
int ImportRgbdObjectsCommand(const DatasetOptions& o, const std::vector<std::string>& command_line) {
  const auto start = WallClock::now();
  const training::Dataset d = training::ImportRgbdObjects(o.rgbd_objects, o.out);
  training::SaveDataset(o.out, d);
  const double wall = SecondsSince(start);
  files::WriteJson(o.out / "run.json", files::RunRecord(command_line, 0,
                                                        {{"command", "dataset"},
                                                         {"from_rgbd_objects", o.rgbd_objects.string()},
                                                         {"capture", d.capture},
                                                         {"dataset_wall_s", wall}}));
  std::cout << "Dataset from the RGB-D Object Dataset views in " << o.rgbd_objects.string() << ": " << d.samples.size()
            << " samples (" << d.Labels(perception::LabelKind::kCategory).size() << " categories, "
            << d.Labels(perception::LabelKind::kInstance).size() << " instances), " << d.capture["skipped"].size()
            << " views skipped, in " << o.out.string() << "/, " << std::lround(wall) << " s\n";
  return 0;
}

// `sortcell eval`: the paper's tables for the samples of the model's classes; for samples of other
// categories (an out-of-set object), what they were called and how confidently (out_of_set.h).
int EvalCommand(const perception::RecognitionModel& model, const training::Dataset& d, const EvalOptions& o,
                const std::vector<std::string>& command_line) {
  // Out-of-set samples are classified too: the descriptors must be the model's kind before either path.
  training::CheckDescriptorParams(model, d, o.dataset.string());
  std::vector<int> in_set, out_of_set;
  training::SplitBySet(model, d, in_set, out_of_set);
  const std::string title = "Evaluation of " + o.model.string() + " on " + o.dataset.string();
  nlohmann::json results = nlohmann::json::object();
  std::string summary;
  if (!in_set.empty()) {
    const training::Evaluation e = training::EvaluateModel(model, d, in_set, o.dataset.string());
    training::WriteRecognitionReport(o.out, title, {e});
    results = training::EvaluationJson(e);
    summary = fmt::format("{} samples of its classes: accuracy {}, macro F1 {}", in_set.size(), e.metrics.accuracy,
                          e.metrics.macro_f1);
  }
  if (!out_of_set.empty()) {
    const training::OutOfSetReport report = training::ClassifyOutOfSet(model, d, out_of_set);
    results["out_of_set"] = training::OutOfSetJson(report);
    std::ofstream tables(o.out / "tables.md", in_set.empty() ? std::ios::trunc : std::ios::app);
    tables << (in_set.empty() ? "# " + title + "\n\n" : "\n") << training::OutOfSetMarkdown(report);
    if (!tables) throw std::runtime_error("cannot write '" + (o.out / "tables.md").string() + "'");
    double mean = 0;
    for (const auto& [name, c] : report) {
      for (double confidence : c.confidences) mean += confidence / out_of_set.size();
    }
    summary += fmt::format("{}{} samples of categories it does not know (mean confidence {:.2f})",
                           summary.empty() ? "" : "; ", out_of_set.size(), mean);
  }
  const auto by_instance = training::ClassifyByInstance(model, d);
  results["by_instance"] = training::InstanceJson(by_instance);
  {
    std::ofstream tables(o.out / "tables.md", std::ios::app);
    tables << "\n" << training::InstanceMarkdown(by_instance);
    if (!tables) throw std::runtime_error("cannot write '" + (o.out / "tables.md").string() + "'");
  }
  results["descriptor"] = perception::DescriptorName(model.descriptor);
  results["dataset"] = o.dataset.string();
  results["model"] = o.model.string();
  files::WriteJson(o.out / "results.json", results);
  files::WriteJson(o.out / "run.json", files::RunRecord(command_line, 0, {{"command", "eval"}}));
  std::cout << "Evaluated " << perception::DescriptorTitle(model.descriptor) << ": " << summary << ". Tables in "
            << o.out.string() << "/tables.md\n";
  for (const auto& [instance, r] : by_instance) {
    if (r.known) {
      std::cout << fmt::format("  {} ({}): {:.1f} % of {} called {}\n", instance, r.category,
                               100.0 * r.correct / r.samples, r.samples, r.category);
    }
  }
  return 0;
}

// `sortcell train --objects SET --out MODEL`: the default recipe (the cell's default model's), its
// scenes kept beside the model.
int TrainFromSetCommand(const TrainOptions& o, const std::vector<std::string>& command_line) {
  const files::ObjectSet set = files::LoadObjectSet(o.objects);
  if (o.if_stale && training::TrainedOnIsCurrent(set, o.out, o.scenes)) {
    std::cout << "The model " << o.out.string() << " is current (" << o.out.string()
              << ".trained_on: the same objects, sensor models and recipe): not trained again\n";
    return 0;
  }
  if (o.out.has_parent_path()) files::PrepareOutputDir(o.out.parent_path());
  const std::filesystem::path scenes = o.out.string() + ".scenes";
  const auto start = WallClock::now();
  const perception::RecognitionModel model = training::TrainDefaultRecipe(set, scenes, o.scenes);
  perception::SaveModel(o.out, model);
  // Trained into the model cache with the default --scenes, it is the current default model.
  training::RecordTrainedOn(set, o.out, o.scenes);
  files::WriteJson(scenes / "run.json",
                   files::RunRecord(command_line, 0, {{"command", "train"}, {"objects", o.objects.string()}}));
  std::cout << "Trained the default recipe for " << set.name << " (" << training::DefaultRecipeTitle(o.scenes)
            << "): " << model.classes.size() << " " << ToString(model.label_kind) << " classes, grouped-CV accuracy "
            << model.cv_accuracy << ", " << std::lround(SecondsSince(start)) << " s. Model " << o.out.string()
            << ", its scenes in " << scenes.string() << "/\n";
  return 0;
}

int TrainFromDatasetCommand(const TrainOptions& o) {
  training::TrainRequest request;
  request.descriptor = perception::ParseDescriptorKind(o.descriptor);
  request.label_kind = ParseOption("--label", o.label, perception::ParseLabelKind);
  request.group_by = ParseOption("--group-by", o.group_by, training::ParseGrouping);
  const training::Dataset d = training::LoadDataset(o.dataset);
  if (o.out.has_parent_path()) files::PrepareOutputDir(o.out.parent_path());
  const auto start = WallClock::now();
  const perception::RecognitionModel model = training::TrainModel(d, {}, request);
  perception::SaveModel(o.out, model);
  training::ForgetTrainedOn(o.out);  // Written over a recipe's model, it is that model no more.
  std::cout << "Trained " << perception::DescriptorTitle(model.descriptor) << " on " << d.samples.size() << " samples, "
            << model.classes.size() << " " << ToString(model.label_kind) << " classes: C " << model.classifier.C()
            << ", gamma " << model.classifier.gamma() << ", grouped-CV accuracy " << model.cv_accuracy << ", "
            << model.classifier.support_vectors() << " support vectors, " << std::lround(SecondsSince(start))
            << " s. Model " << o.out.string() << "\n";
  return 0;
}

// The simulated capture the options ask for: random cell scenes, or turntable views.
training::Dataset CaptureSimulated(const DatasetOptions& o, const files::ObjectSet& set) {
  if (o.scenes > 0) {
    training::SceneOptions options;
    options.scenes = o.scenes;
    options.seed = o.seed;
    options.max_objects = std::min<int>(options.max_objects, static_cast<int>(set.objects.size()));
    options.min_objects = std::min(options.min_objects, options.max_objects);
    options.modes.clear();
    for (const auto& mode : o.placement) options.modes.push_back(*sim::ParsePlacementMode(mode));  // Checked.
    options.placement.lying_fraction = o.lying_fraction;
    options.colour_jitter = o.colour_jitter;
    options.depth_noise_max = o.depth_noise_max;
    options.fits_familiarity = !o.classifier_only;
    return training::CaptureScenes(set, options, o.out);
  }
  training::TurntableOptions options;
  options.views = o.views;
  options.seed = o.seed;
  options.occluded_copies = o.occluded;
  return training::CaptureTurntable(set, options, o.out);
}

int RunDatasetCommand(const DatasetOptions& o, const std::vector<std::string>& command_line) {
  if (!o.rgbd_objects.empty()) return ImportRgbdObjectsCommand(o, command_line);
  if (o.objects.empty()) {
    throw std::invalid_argument("dataset: give --objects SET.yaml (a simulated capture) or --from-rgbd-objects DIR");
  }
  const files::ObjectSet set = files::LoadObjectSet(o.objects);
  const auto start = WallClock::now();
  const training::Dataset d = CaptureSimulated(o, set);
  training::SaveDataset(o.out, d);
  const double wall = SecondsSince(start);
  files::WriteJson(
      o.out / "run.json",
      files::RunRecord(
          command_line, o.seed,
          {{"command", "dataset"}, {"objects", o.objects.string()}, {"capture", d.capture}, {"dataset_wall_s", wall}}));
  std::cout << "Dataset of " << set.name << ": " << d.samples.size() << " samples ("
            << d.Labels(perception::LabelKind::kCategory).size() << " categories, "
            << d.Labels(perception::LabelKind::kInstance).size() << " instances) in " << o.out.string() << "/, "
            << std::lround(wall) << " s\n";
  return 0;
}

}  // namespace

void AddDatasetCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<DatasetOptions>();
  CLI::App* cmd = app.add_subcommand(
      "dataset",
      "Capture a recognition dataset of an object set: each instance alone on a virtual turntable seen from "
      "30, 45 and 60 degrees elevation (~1 m), --views views per revolution, lighting and pose jitter "
      "randomised, Kinect noise on; each capture segmented and described. With --scenes N: N random cell "
      "scenes of the set's objects instead (a test set like the paper's real scenes). Writes manifest.json "
      "(labels: category, instance, elevation, frame), descriptors.csv (raw HSV 192 + CVFH 308 per sample), "
      "clouds/*.pcd and run.json. With --from-rgbd-objects DIR: the real views of the RGB-D Object Dataset "
      "(Lai et al. 2011) in DIR instead, as it is published (<category>/<instance>/"
      "<instance>_<video>_<frame>_crop.png, _depthcrop.png, _maskcrop.png, _loc.txt).");
  CLI::Option* objects = cmd->add_option("--objects", o->objects, "Object set YAML, e.g. scenes/objects/paper.yaml");
  CLI::Option* rgbd = cmd->add_option("--from-rgbd-objects", o->rgbd_objects,
                                      "A folder of the RGB-D Object Dataset's views (instead of --objects)");
  objects->excludes(rgbd);
  cmd->add_option("--out", o->out, "Dataset folder (created if missing)")->required();
  CLI::Option* views = cmd->add_option("--views", o->views, "Views per revolution and elevation")
                           ->check(CLI::Range(3, 3600))
                           ->capture_default_str();
  CLI::Option* scenes =
      cmd->add_option("--scenes", o->scenes, "Random cell scenes instead of turntable views (0: turntable)")
          ->check(CLI::Range(0, 100000))
          ->capture_default_str();
  CLI::Option* seed =
      cmd->add_option("--seed", o->seed, "Seed (uint64)")->check(kUnsignedInteger)->capture_default_str();
  CLI::Option* occluded =
      cmd->add_option("--occluded", o->occluded,
                      "Turntable: per view, this many more samples with 15-70 % of the object hidden beyond a "
                      "random straight edge (as a nearer object hides it in a scene)")
          ->check(CLI::Range(0, 10))
          ->capture_default_str();
  occluded->excludes(scenes);
  CLI::Option* placement =
      cmd->add_option("--placement", o->placement,
                      "Scenes: how objects stand, as in episodes: sparse (apart), dense (touching), clustered (groups "
                      "of 2-4); a comma list takes turns scene by scene, e.g. sparse,dense,clustered")
          ->delimiter(',')
          ->check(CLI::IsMember(AllNames(sim::kPlacementModeNames)))
          ->capture_default_str();
  CLI::Option* lying = cmd->add_option("--lying-fraction", o->lying_fraction,
                                       "Scenes: chance (0-1) that a bottle or box lies on its side")
                           ->check(CLI::Range(0.0, 1.0))
                           ->capture_default_str();
  CLI::Option* jitter = cmd->add_option("--colour-jitter", o->colour_jitter,
                                        "Scenes: each scene's objects' colours varied at a level drawn from [0, J], as "
                                        "the episodes' colour_jitter varies them (0-1)")
                            ->check(CLI::Range(0.0, 1.0))
                            ->capture_default_str();
  CLI::Option* depth_noise =
      cmd->add_option("--depth-noise-max", o->depth_noise_max,
                      "Scenes: each scene's Kinect depth noise scaled by a factor drawn from [1, M] (1: the Kinect's)")
          ->check(CLI::Range(1.0, 5.0))
          ->capture_default_str();
  CLI::Option* classifier_only =
      cmd->add_flag("--classifier-only", o->classifier_only,
                    "Scenes: the views train a model's classifier but not its familiarity (for views through a widened "
                    "sensor: jittered colours, noisier depth)");
  for (CLI::Option* scene_only : {placement, lying, jitter, depth_noise, classifier_only}) scene_only->needs(scenes);
  for (CLI::Option* simulated : {views, scenes, seed, occluded, placement, lying, jitter, depth_noise, classifier_only})
    rgbd->excludes(simulated);
  cmd->callback([&run, o, command_line] { run = [o, command_line] { return RunDatasetCommand(*o, command_line); }; });
}

void AddTrainCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* cmd = app.add_subcommand(
      "train",
      "Train a multi-class RBF SVM (libsvm) on a dataset with one descriptor. Features are scaled to [0, 1] "
      "histogram by histogram (hue, saturation, value, CVFH's five blocks: each by its range over the training "
      "data); (C, gamma) come from a grid searched with grouped 3-fold "
      "cross-validation (groups: contiguous thirds of each turntable revolution, or whole instances). The "
      "model file holds the descriptor, its parameters, the classes, the scaling, the familiarity (fitted on the "
      "samples not captured --classifier-only) and a format version. With "
      "--objects SET instead of --dataset: the default recipe for that set, the one episodes and sweeps train "
      "on first use (" +
          training::DefaultRecipeTitle() + "), its scenes kept in MODEL.scenes/.");
  CLI::Option* dataset = cmd->add_option("--dataset", o->dataset, "Dataset folder from sortcell dataset");
  CLI::Option* objects = cmd->add_option("--objects", o->objects, "Object set YAML: train the default recipe on it");
  dataset->excludes(objects);
  CLI::Option* descriptor =
      cmd->add_option("--descriptor", o->descriptor, "cvfh | color-cvfh | color-cvfh-norm")->capture_default_str();
  cmd->add_option("--out", o->out, "Model file to write, e.g. out/models/paper.model.json")->required();
  CLI::Option* label =
      cmd->add_option("--label", o->label, "What to recognise: category | instance")->capture_default_str();
  CLI::Option* group =
      cmd->add_option("--group-by", o->group_by, "Cross-validation groups: sequence | instance")->capture_default_str();
  cmd->add_flag(
         "--if-stale", o->if_stale,
         "With --objects: train only if MODEL is missing, has no MODEL.trained_on (the digest train --objects "
         "writes), or its MODEL.trained_on names other objects, sensor models or another recipe (another --scenes too)")
      ->needs(objects);
  cmd->add_option("--scenes", o->scenes,
                  "With --objects: random cell scenes of the set's own objects (the training variety's and the widened "
                  "twin's in proportion); fewer for a quick trial model. A model of another count is not the model "
                  "cache's default")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str()
      ->needs(objects);
  for (CLI::Option* recipe_fixed : {descriptor, label, group}) objects->excludes(recipe_fixed);
  cmd->callback([&run, o, command_line] {
    run = [o, command_line] {
      if (!o->objects.empty()) return TrainFromSetCommand(*o, command_line);
      if (o->dataset.empty()) throw std::invalid_argument("train: give --dataset DIR or --objects SET.yaml");
      return TrainFromDatasetCommand(*o);
    };
  });
}

void AddEvalCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Classify every sample of a dataset with a model and write the paper's tables: per class one-vs-all "
      "recall, precision, accuracy, F1 and the confusion matrix in percent (tables.md, metrics.csv, "
      "confusion_<descriptor>.csv/.png), results.json and run.json. Samples of categories the model does not "
      "know (an out-of-set object) are reported apart: what they were called, the confidence distribution and "
      "the share a --reject-below threshold would reject (results.json out_of_set, tables.md).");
  cmd->add_option("--dataset", o->dataset, "Dataset folder from sortcell dataset")->required();
  cmd->add_option("--model", o->model, "Model file from sortcell train")->required();
  cmd->add_option("--out", o->out, "Output folder (created if missing)")->required();
  cmd->callback([&run, o, command_line] {
    run = [o, command_line] {
      const perception::RecognitionModel model = perception::LoadModel(o->model);
      const training::Dataset d = training::LoadDataset(o->dataset);
      files::PrepareOutputDir(o->out);
      return EvalCommand(model, d, *o, command_line);
    };
  });
}

}  // namespace sortcell::app
