// The sharded-sweep recipe for GNU parallel in docs/sorting-and-sweeps.md (`sortcell sweep`), run as written (read
// from that page, with the test's spec and output folder for its SPEC and OUT and this build's sortcell):
// shards in parallel, merged, --resume writing the summary, which must equal the unsharded run's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"
#include "source_tree.h"

namespace {

using sortcell_test::kSource;

using sortcell_test::ReadFile;

// The recipe's commands: the lines after its "SPEC=... OUT=..." line up to the Slurm comment.
std::string ParallelRecipe() {
  const std::string readme = ReadFile(kSource + "/docs/sorting-and-sweeps.md");
  const size_t heading = readme.find("# GNU parallel");
  const size_t first = readme.find('\n', readme.find("SPEC=", heading)) + 1;
  const size_t last = readme.find("# Slurm", first);
  if (heading == std::string::npos || last == std::string::npos) return "";
  std::string recipe = readme.substr(first, last - first);
  for (size_t at; (at = recipe.find("./build/app/sortcell")) != std::string::npos;) {
    recipe.replace(at, std::string("./build/app/sortcell").size(), SORTCELL_BINARY);
  }
  return recipe;
}

TEST(ReadmeRecipe, GnuParallelShardsMergeToTheUnshardedSummary) {
  if (std::system("command -v parallel > /dev/null 2>&1") != 0) GTEST_SKIP() << "GNU parallel is not installed";
  const std::string recipe = ParallelRecipe();
  ASSERT_NE(recipe.find("parallel "), std::string::npos) << "no recipe found in docs/sorting-and-sweeps.md";
  const sortcell_test::TempDir dir("recipe");
  const std::string spec = (dir / "spec.yaml").string(), out = (dir / "out").string();
  std::ofstream(spec) << "scene: " << kSource << "/scenes/cell.xml\nobject_set: " << kSource
                      << "/scenes/objects/paper.yaml\nmodel: " << SORTCELL_TEST_MODEL
                      << "\nseed: 40\nepisodes: 4\naxes:\n  objects: [1, 2]\n";
  std::ofstream(dir / "recipe.sh") << "set -e\nSPEC=" << spec << " OUT=" << out << "\n" << recipe;
  ASSERT_EQ(std::system(("cd " + dir.str() + " && bash recipe.sh > recipe.log 2>&1").c_str()), 0)
      << ReadFile((dir / "recipe.log").string());
  const auto unsharded = sortcell_test::RunSortcell("sweep " + spec + " -j 2 --out " + (dir / "whole").string());
  ASSERT_EQ(unsharded.exit_code, 0) << unsharded.err;
  nlohmann::json merged = nlohmann::json::parse(ReadFile(out + "/merged/summary.json"));
  nlohmann::json whole = nlohmann::json::parse(ReadFile((dir / "whole" / "summary.json").string()));
  EXPECT_EQ(merged["episodes"], 4);
  EXPECT_EQ(sortcell_test::SummaryWithoutMachineFigures(merged), sortcell_test::SummaryWithoutMachineFigures(whole));
}

}  // namespace
