// The default recipe as the cell's default models get it (label sim, CTest fixture episode_model): the
// episodes' model, made by `sortcell train --objects scenes/objects/paper.yaml` without --scenes, is
// trained on 150 random cell scenes of the set and as many through the widened sensor, and counts as
// current. (RecognitionE2e.TrainFromATinySetWithTheDefaultRecipe runs the command on a tiny set with fewer
// scenes.)
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>
#include <string>

#include "run_sortcell.h"
#include "source_tree.h"

namespace {

TEST(DefaultRecipe, TheEpisodesModelIsTrainedOn150ScenesAndTheirWidenedTwin) {
  const std::string model = SORTCELL_TEST_MODEL;
  std::ifstream in(model + ".scenes/manifest.json");
  ASSERT_TRUE(in) << model << ".scenes/manifest.json";
  const nlohmann::json scenes = nlohmann::json::parse(in);
  const nlohmann::json& groups = scenes["capture"]["groups"];
  ASSERT_EQ(groups.size(), 2u) << scenes["capture"];
  EXPECT_EQ(groups[0]["scenes"], 150);
  EXPECT_EQ(groups[0]["fits_familiarity"], true);
  EXPECT_EQ(groups[1]["scenes"], 150) << "the widened twin";
  EXPECT_EQ(groups[1]["fits_familiarity"], false);
  std::set<int> seen;
  for (const auto& s : scenes["samples"]) seen.insert(s["scene"].get<int>());
  EXPECT_EQ(seen.size(), 300u) << "every scene has an object in view";
  const auto again =
      sortcell_test::RunSortcell("train --if-stale --objects " +
                                 (sortcell_test::kRoot / "scenes/objects/paper.yaml").string() + " --out " + model);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("is current"), std::string::npos) << again.out;
}

}  // namespace
