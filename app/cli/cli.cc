#include "app/cli/cli.h"

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/calibrate_command.h"
#include "app/cli/cell_command.h"
#include "app/cli/capture_command.h"
#include "app/cli/objects_command.h"
#include "app/cli/classify_command.h"
#include "app/cli/compare_command.h"
#include "app/cli/episode_command.h"
#include "app/cli/experiment_command.h"
#include "app/cli/kinematics_commands.h"
#include "app/cli/pick_command.h"
#include "app/cli/recognition_commands.h"
#include "app/cli/replay_command.h"
#include "app/cli/report_command.h"
#include "app/cli/segment_command.h"
#include "app/cli/sweep_command.h"
#include "app/cli/views_command.h"

namespace sortcell::app {
namespace {

std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

// Every subcommand, each filling `run` when it is the one parsed.
void AddCommands(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  AddCaptureCommand(app, run, command_line);
  AddPickCommand(app, run, command_line);
  AddSegmentCommand(app, run, command_line);
  AddDatasetCommand(app, run, command_line);
  AddTrainCommand(app, run, command_line);
  AddEvalCommand(app, run, command_line);
  AddClassifyCommand(app, run);
  AddExperimentCommand(app, run, command_line);
  AddEpisodeCommand(app, run, command_line);
  AddCalibrateCommand(app, run, command_line);
  AddSweepCommand(app, run, command_line);
  AddCompareCommand(app, run, command_line);
  AddReplayCommand(app, run);
  AddReportCommand(app, run);
  AddKinematicsCommands(app, run);
  AddObjectsCommand(app, run, command_line);
  AddCellCommand(app, run, command_line);
  AddViewsCommand(app, run);
}

// CLI11's refusal in one line; an unknown first word is named with the commands there are.
std::string ParseErrorMessage(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::string message = OneLine(e.what());
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
    message = "unknown command '" + std::string(argv[1]) + "' (commands: " + names + ")";
  }
  return message;
}

}  // namespace

int RunCli(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("sortcell"));
  spdlog::set_pattern("[%l] %v");
  const std::vector<std::string> command_line(argv, argv + argc);

  CLI::App app{
      "SortCell: a simulated robotic sorting cell (UR5, parallel gripper, Kinect v1, Color-CVFH + SVM).\n"
      "World frame = UR Base frame (D-H frame 0), z up, table top at z = 0."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("sortcell ") + SORTCELL_VERSION, "Print the version and exit");
  std::function<int()> run;
  AddCommands(app, run, command_line);

  // `sortcell episode|calibrate --set KEY=VALUE` becomes `--KEY=VALUE` before CLI11 parses
  // (episode_command.h).
  std::vector<std::string> args = command_line;
  if (args.size() > 1 && (args[1] == "episode" || args[1] == "calibrate")) {
    try {
      args = ExpandEpisodeSets(*app.get_subcommand(args[1]), args);
    } catch (const std::invalid_argument& e) {
      std::cerr << "sortcell " << args[1] << ": error: " << OneLine(e.what()) << "\n";
      return 2;
    }
  }
  std::vector<char*> arg_pointers;
  for (std::string& a : args) arg_pointers.push_back(a.data());

  try {
    app.parse(static_cast<int>(arg_pointers.size()), arg_pointers.data());
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    std::cerr << "sortcell: error: " << ParseErrorMessage(app, e, argc, argv) << " (see sortcell --help)\n";
    return 2;
  }
  try {
    return run ? run() : 2;
  } catch (const std::exception& e) {
    std::cerr << "sortcell " << (app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name())
              << ": error: " << OneLine(e.what()) << "\n";
    return 2;
  }
}

}  // namespace sortcell::app
