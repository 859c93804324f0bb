// The default reject threshold (scenes/cells/default_reject.yaml's reject_below) on the episode model
// (CTest fixture episode_model, the paper set's default model): fresh cell scenes of the objects it was
// trained on are rarely rejected, cell scenes of produce it never saw mostly are.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <spdlog/fmt/fmt.h>

#include "files/cell_file.h"
#include "run_sortcell.h"
#include "source_tree.h"

namespace {

namespace fs = std::filesystem;
using sortcell_test::kSource;
using sortcell_test::RunSortcell;
using sortcell_test::TempPath;

// `eval` of the episode model on `scenes` fresh random cell scenes of `objects` (seed 9000: scenes the
// model's 150 training scenes do not hold); its results.json.
nlohmann::json EvalOnScenes(const std::string& objects, int scenes) {
  const fs::path data = TempPath("reject_" + objects), out = TempPath("reject_" + objects + "_eval");
  const auto d = RunSortcell("dataset --objects " + kSource + "/scenes/objects/" + objects + ".yaml --scenes " +
                             std::to_string(scenes) + " --seed 9000 --placement sparse,dense --out " + data.string());
  EXPECT_EQ(d.exit_code, 0) << d.err;
  const auto e =
      RunSortcell("eval --dataset " + data.string() + " --model " + SORTCELL_TEST_MODEL + " --out " + out.string());
  EXPECT_EQ(e.exit_code, 0) << e.err;
  return nlohmann::json::parse(std::ifstream(out / "results.json"));
}

double DefaultRejectBelow() {
  return sortcell::files::ReadCellFile(kSource + "/scenes/cells/default_reject.yaml").rules.reject_below;
}

TEST(RejectThreshold, TheDefaultRejectsFewKnownViewsAndMostUnknownOnes) {
  const double threshold = DefaultRejectBelow();
  ASSERT_GT(threshold, 0.0);
  const std::string key = fmt::format("{:g}", threshold);

  const nlohmann::json known = EvalOnScenes("paper", 12);
  int known_views = 0;
  double known_rejected = 0;
  for (const auto& [name, instance] : known["by_instance"].items()) {
    ASSERT_TRUE(instance["known"].get<bool>()) << name;
    known_views += instance["samples"].get<int>();
    known_rejected += instance["samples"].get<int>() * instance["rejected_below"][key].get<double>();
  }
  ASSERT_GE(known_views, 40);
  // About 5 % by construction (held-out scenes); 15 % leaves room for a dozen scenes' chance.
  EXPECT_LE(known_rejected / known_views, 0.15) << known_rejected << " of " << known_views;

  const nlohmann::json unknown = EvalOnScenes("produce_one_each", 12);
  int unknown_views = 0;
  double unknown_rejected = 0;
  for (const auto& [name, category] : unknown["out_of_set"].items()) {
    unknown_views += category["samples"].get<int>();
    unknown_rejected += category["samples"].get<int>() * category["rejected_below"][key].get<double>();
  }
  ASSERT_GE(unknown_views, 30);
  EXPECT_GE(unknown_rejected / unknown_views, 0.75) << unknown_rejected << " of " << unknown_views;
}

}  // namespace
