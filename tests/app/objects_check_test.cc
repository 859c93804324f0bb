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

// Our own produce written as URDF objects the way the YCB scans are published (models/tools/export_urdf.py):
// a set no code knows, imported through the same path, each with its texture, its mass and its size.
TEST(ObjectsCheck, OurProduceWrittenAsUrdfObjectsImportsWithTheirMassAndSize) {
  sortcell_test::TempDir dir;
  ::setenv("SORTCELL_IMPORT_CACHE", (dir.path() / "cache").c_str(), 1);
  const std::string source = SORTCELL_SOURCE_DIR;
  const auto set = dir.path() / "urdf";
  const std::string export_command = "python3 " + source + "/models/tools/export_urdf.py " + source +
                                     "/scenes/objects/produce.yaml --per-category 1 --out " + set.string() + " > " +
                                     (dir.path() / "export.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(export_command.c_str()), 0) << export_command;
  const auto out = dir.path() / "out";
  const auto r =
      sortcell_test::RunSortcell("objects check " + (set / "objects.yaml").string() + " --out " + out.string());
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err << r.out;  // 1: a plate is too wide to grasp
  const auto check = nlohmann::json::parse(std::ifstream(out / "check.json"));
  ASSERT_EQ(check.at("objects").size(), 10u);  // one of each produce category
  for (const auto& thing : check.at("objects")) {
    const auto& import = thing.at("import");
    EXPECT_EQ(import.at("collision_pieces"), 1) << thing.dump();
    // The plate's dish is concave (it collides as its hull, the importer warns) and too wide to grasp.
    const bool plate = thing.at("category") == "plate";
    EXPECT_EQ(import.at("warnings").size(), plate ? 2u : 0u) << thing.dump();
    EXPECT_EQ(thing.at("graspable").get<bool>(), !plate) << thing.dump();
  }
  // apple1 as make_produce.py wrote it: 0.077 x 0.073 x 0.057 m, 0.131 kg.
  const auto& apple = check.at("objects").at(0).at("import");
  EXPECT_DOUBLE_EQ(apple.at("mass_kg").get<double>(), 0.131);
  const double size[3] = {0.077, 0.073, 0.057};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(apple.at("size_m")[i].get<double>(), size[i], 0.001) << i;
}

}  // namespace
