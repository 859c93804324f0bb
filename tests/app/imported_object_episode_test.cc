// An episode that sorts a user's object: imported from its URDF (tests/assets/user_objects.h: a
// textured block with a handle, its collision a two-piece decomposition), beside our ball, in the
// default cell composed with the set; a model trained on the set's cell scenes; both seen,
// recognised, grasped by friction and put into their categories' bins.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../assets/user_objects.h"
#include "run_sortcell.h"
#include "source_tree.h"
#include "temp_dir.h"

namespace {

TEST(ImportedObjectEpisode, AUserObjectFromItsUrdfIsSortedIntoItsBin) {
  sortcell_test::TempDir dir;
  ::setenv("SORTCELL_IMPORT_CACHE", (dir.path() / "cache").c_str(), 1);
  const auto user = sortcell_test::WriteUserObject(dir.path() / "user");
  const auto set = dir.path() / "set.yaml";
  std::ofstream(set) << "name: mine\nobjects:\n  - {name: thing, category: others, instance: thing, urdf: "
                     << user.urdf.string()
                     << "}\n  - {name: ball, category: ball, instance: ball, model: " << sortcell_test::kSource
                     << "/models/objects/ball.inc.xml}\n";
  // The set's own model, from random cell scenes of it (fewer than the default recipe's, for time).
  const auto data = dir.path() / "scenes", model = dir.path() / "model.json";
  ASSERT_EQ(
      sortcell_test::RunSortcell("dataset --objects " + set.string() + " --scenes 30 --out " + data.string()).exit_code,
      0);
  ASSERT_EQ(sortcell_test::RunSortcell("train --dataset " + data.string() + " --descriptor color-cvfh-norm --out " +
                                       model.string())
                .exit_code,
            0);
  const auto out = dir.path() / "episode";
  const auto r = sortcell_test::RunSortcell(
      "episode --scene " + sortcell_test::kCell + " --object-set " + set.string() + " --model " + model.string() +
      " --seed 3 --place thing=0.5,0.05,0.4 " + "--place ball=0.45,-0.15 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto metrics = nlohmann::json::parse(std::ifstream(out / "metrics.json"));
  ASSERT_EQ(metrics["items"].size(), 2u);
  for (const auto& item : metrics["items"]) EXPECT_EQ(item["outcome"], "sorted") << item.dump();
}

}  // namespace
