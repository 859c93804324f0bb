#include "app/cli/compare_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "files/output_dir.h"
#include "app/sweep/sweep_compare.h"

namespace sortcell::app {
namespace {

struct CompareCli {
  std::filesystem::path a, b, out;
};

}  // namespace

void AddCompareCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto cli = std::make_shared<CompareCli>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare two sweep folders of the same episodes (a change's before A and after B): both correct-sort rates "
      "with their 95 % intervals, the exact McNemar test on the items paired by episode and name (is the "
      "difference significant?) and every item whose outcome changed. Printed, and written as compare.html and "
      "compare.json.");
  cmd->add_option("a", cli->a, "Sweep folder before (A)")->required();
  cmd->add_option("b", cli->b, "Sweep folder after (B)")->required();
  cmd->add_option("--out", cli->out, "Output folder for compare.html and compare.json (created if missing)")
      ->required();
  cmd->callback([&run, cli, command_line] {
    run = [cli, command_line] {
      const SweepComparison c = CompareSweepFolders(cli->a, cli->b);
      files::PrepareOutputDir(cli->out);
      files::WriteTextFile(cli->out / "compare.html", ComparisonHtml(c, cli->a, cli->b, cli->out));
      files::WriteJson(cli->out / "compare.json", ComparisonJson(c, cli->a, cli->b));
      files::WriteJson(cli->out / "run.json", files::RunRecord(command_line, 0, {{"command", "compare"}}));
      std::fputs(ComparisonText(c, cli->a, cli->b).c_str(), stdout);
      std::printf("Page: %s\n", (cli->out / "compare.html").string().c_str());
      return 0;
    };
  });
}

}  // namespace sortcell::app
