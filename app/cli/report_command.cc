#include "app/cli/report_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/sweep/sweep_html_report.h"

namespace sortcell::app {

void AddReportCommand(CLI::App& app, std::function<int()>& run) {
  auto dir = std::make_shared<std::filesystem::path>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write a sweep folder's report page, DIR/report/index.html: the summary, the correct-sort rate by axis value "
      "and by object and the cycle by phase (interactive plots), every episode in a table that sorts and filters, "
      "and every failed item (after `sweep --review`: its attempts in words and its clip). Opens offline.");
  cmd->add_option("dir", *dir, "Sweep folder (holding summary.json and results.jsonl)")->required();
  cmd->callback([&run, dir] {
    run = [dir] {
      std::printf("Report: %s\n", WriteHtmlReport(*dir).string().c_str());
      return 0;
    };
  });
}

}  // namespace sortcell::app
