// `sortcell objects check` on a user's object: imported, dropped on the table, found resting on its
// flat base, with a still and a scene file whose keyframe holds it at rest.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../assets/user_objects.h"
#include "run_sortcell.h"
#include "sim/model.h"
#include "temp_dir.h"

namespace {

TEST(ObjectsCheck, AnImportedObjectRestsOnTheTable) {
  sortcell_test::TempDir dir;
  ::setenv("SORTCELL_IMPORT_CACHE", (dir.path() / "cache").c_str(), 1);
  const auto user = sortcell_test::WriteUserObject(dir.path() / "user");
  const std::string set = sortcell_test::SetWith(dir.path(), user.urdf.string());
  const auto out = dir.path() / "out";
  const auto r = sortcell_test::RunSortcell("objects check " + set + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto check = nlohmann::json::parse(std::ifstream(out / "check.json"));
  const auto& thing = check.at("objects").at(0);
  EXPECT_TRUE(thing.at("rests").get<bool>()) << thing.dump();
  EXPECT_TRUE(thing.at("graspable").get<bool>()) << thing.dump();
  EXPECT_EQ(thing.at("import").at("collision_pieces"), 2);
  EXPECT_LT(thing.at("tilt_deg").get<double>(), 2.0);  // stands on its flat base
  EXPECT_TRUE(std::filesystem::exists(out / "objects_1.png"));
  // mujoco-simulate opens the scene; its keyframe "checked" has the object where it came to rest.
  const sortcell::sim::Model scene = sortcell::sim::Model::FromFile((out / "scene.xml").string());
  const int key = mj_name2id(scene.get(), mjOBJ_KEY, "checked");
  ASSERT_GE(key, 0);
  const int body = scene.Id(mjOBJ_BODY, thing.at("name").get<std::string>());
  const double* p = scene->key_qpos + key * scene->nq + scene->jnt_qposadr[scene->body_jntadr[body]];
  const auto settled = thing.at("settled_at_m");
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(p[i], settled[i].get<double>(), 1e-6) << i;
}

}  // namespace
