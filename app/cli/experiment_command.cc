#include "app/cli/experiment_command.h"

#include <iostream>
#include <memory>

#include "app/cli/cli_validators.h"

namespace sortcell::app {

void AddExperimentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<training::ExperimentOptions>();
  auto split = std::make_shared<std::string>(ToString(o->split));
  CLI::App* cmd = app.add_subcommand(
      "experiment",
      "Run one of the paper's recognition experiments whole (section 3, Tables 1-8): 1 = category level on the "
      "produce set, 2 = instance level on the apple and orange instances, 3 = the six paper objects tested in random "
      "cell "
      "scenes. Captures the data into DIR/data (reused when it matches), trains and evaluates CVFH, Color-CVFH and "
      "Color-CVFH (normalization), and writes tables.md, metrics.csv, confusion_*.csv/.png, results.json, models/.");
  cmd->add_option("experiment", o->number, "1, 2 or 3")->required()->check(CLI::IsMember({1, 2, 3}));
  cmd->add_option("--split", *split, "paper | unseen-instance (experiment 1 only)")->capture_default_str();
  cmd->add_option("--trials", o->trials,
                  "unseen-instance: trials, each holding out one instance per category (default 0: until every "
                  "instance has been held out once)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--views", o->views, "Turntable views per revolution and elevation")
      ->check(CLI::Range(3, 3600))
      ->capture_default_str();
  cmd->add_option("--scenes", o->scenes, "Experiment 3: random cell scenes to test on")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed (uint64)")->check(kUnsignedInteger)->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder (created if missing)")->required();
  cmd->add_option("--data", o->data,
                  "Folder of the captured datasets, reused when they match (default DIR/data); experiments 1 "
                  "and 2 share the produce turntable data. A folder holding one dataset (manifest.json, e.g. "
                  "from `dataset --from-rgbd-objects`): experiments 1 and 2 run on it instead");
  cmd->callback([&run, o, split, command_line] {
    run = [o, split, command_line] {
      o->split = ParseOption("--split", *split, training::ParseExperimentSplit);
      const nlohmann::json r = training::RunExperiment(*o, command_line);
      std::cout << "Experiment " << o->number << " (" << ToString(o->split) << "): " << r["train_samples"]
                << " training, " << r["test_samples"] << " test samples. Macro F1:";
      for (const auto& [name, d] : r["descriptors"].items())
        std::cout << " " << name << " " << d["macro_f1"].get<double>();
      std::cout << ". Tables in " << o->out.string() << "/tables.md\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
