// Object set YAML files: parsed into plain structs, every mistake named.
#include "files/object_set.h"
#include "files/output_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.h"

namespace {

using sortcell::files::LoadObjectSet;

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = sortcell_test::TestTempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::string& path) {
  try {
    sortcell::files::LoadObjectSet(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

const std::string kModel = std::string("model: ") + SORTCELL_SOURCE_DIR + "/models/objects/ball.inc.xml";

TEST(ObjectSet, LoadsThePaperSet) {
  const auto set = sortcell::files::LoadObjectSet(SORTCELL_SOURCE_DIR "/scenes/objects/paper.yaml");
  EXPECT_EQ(set.name, "paper");
  ASSERT_EQ(set.objects.size(), 6u);
  EXPECT_EQ(set.Find("bottle2").category, "others");
  EXPECT_TRUE(set.Find("ball").model.is_absolute());
  EXPECT_THROW(set.Find("teapot"), std::invalid_argument);
}

TEST(ObjectSet, RejectsUnknownKeysByName) {
  const auto path = Write("unknown.yaml",
                          "name: s\nobjects:\n  - {name: a, category: c, instance: a, colour: red, " + kModel + "}\n");
  const std::string e = ErrorOf(path);
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'colour' in objects[0]"), std::string::npos) << e;
  const std::string top = ErrorOf(Write("unknown_top.yaml", "name: s\nobject: []\n"));
  EXPECT_NE(top.find("unknown key 'object'"), std::string::npos) << top;
}

TEST(ObjectSet, RejectsWrongTypesMissingKeysDuplicatesAndMissingModels) {
  EXPECT_NE(
      ErrorOf(Write("type.yaml", "name: s\nobjects:\n  - {name: [a], category: c, instance: a, " + kModel + "}\n"))
          .find("'objects[0].name': expected a non-empty string, found a list"),
      std::string::npos);
  EXPECT_NE(ErrorOf(Write("missing.yaml", "name: s\nobjects:\n  - {name: a, instance: a, " + kModel + "}\n"))
                .find("missing key 'category' in objects[0]"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Write("dup.yaml", "name: s\nobjects:\n  - {name: a, category: c, instance: a, " + kModel +
                                          "}\n  - {name: a, category: c, instance: b, " + kModel + "}\n"))
                .find("duplicate object name 'a'"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(Write("nomodel.yaml", "name: s\nobjects:\n  - {name: a, category: c, instance: a, model: no.xml}\n"))
          .find("'objects[0].model': file"),
      std::string::npos);
  EXPECT_NE(ErrorOf(Write("empty.yaml", "name: s\nobjects: []\n")).find("expected a non-empty list"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Write("bad.yaml", "name: [unclosed\n")).find("not valid YAML"), std::string::npos);
  EXPECT_NE(ErrorOf("/nonexistent/set.yaml").find("file not found"), std::string::npos);
}

}  // namespace

namespace {

TEST(ObjectSet, TheModelsDigestChangesWithAModelOrATexture) {
  const std::string dir = sortcell_test::TestTempDir() + "digest/";
  std::filesystem::create_directories(dir + "textures");
  std::ofstream(dir + "a.inc.xml") << "<mujoco/>";
  std::ofstream(dir + "textures/a.png") << "png 1";
  const auto set = sortcell::files::LoadObjectSet(Write(
      "digest.yaml", "name: d\nobjects:\n  - {name: a, category: c, instance: a, model: " + dir + "a.inc.xml}\n"));
  const std::string first = sortcell::files::ObjectModelsDigest(set, dir + "textures");
  EXPECT_EQ(sortcell::files::ObjectModelsDigest(set, dir + "textures"), first);
  std::ofstream(dir + "textures/a.png") << "png 2";
  const std::string second = sortcell::files::ObjectModelsDigest(set, dir + "textures");
  EXPECT_NE(second, first);
  std::ofstream(dir + "a.inc.xml") << "<mujoco><!-- moved --></mujoco>";
  EXPECT_NE(sortcell::files::ObjectModelsDigest(set, dir + "textures"), second);
  EXPECT_EQ(sortcell::files::ObjectModelsDigest(set, dir + "no_textures").size(), 16u);
}

TEST(ObjectSet, ATrainingVarietyAddsObjectsOfTheSetsCategoriesForTrainingOnly) {
  const auto variety =
      Write("variety.yaml", "name: v\nobjects:\n  - {name: v1, category: ball, instance: v1, " + kModel +
                                "}\n  - {name: v2, category: ball, instance: v2, " + kModel + "}\n");
  const auto path =
      Write("with_variety.yaml", "name: s\ntraining_variety: [" + variety +
                                     "]\nobjects:\n  - {name: a, category: ball, instance: a, " + kModel + "}\n");
  const auto set = sortcell::files::LoadObjectSet(path);
  ASSERT_EQ(set.objects.size(), 1u);
  ASSERT_EQ(set.training_variety.size(), 2u);
  EXPECT_EQ(set.training_variety[1].name, "v2");
  // The variety is part of what the set's model was trained on.
  const auto plain = sortcell::files::LoadObjectSet(
      Write("without_variety.yaml", "name: s\nobjects:\n  - {name: a, category: ball, instance: a, " + kModel + "}\n"));
  EXPECT_NE(sortcell::files::ObjectModelsDigest(set, "none"), sortcell::files::ObjectModelsDigest(plain, "none"));
  // So are the labels (what a model learns), though the model files are the same.
  const auto relabelled = sortcell::files::LoadObjectSet(
      Write("relabelled.yaml", "name: s\nobjects:\n  - {name: a, category: cup, instance: a, " + kModel + "}\n"));
  EXPECT_NE(sortcell::files::ObjectModelsDigest(relabelled, "none"),
            sortcell::files::ObjectModelsDigest(plain, "none"));
}

TEST(ObjectSet, ATrainingVarietyOfAnotherCategoryATakenNameOrItsOwnVarietyIsRefused) {
  const auto other =
      Write("variety_other.yaml", "name: v\nobjects:\n  - {name: v1, category: cup, instance: v1, " + kModel + "}\n");
  const auto taken =
      Write("variety_taken.yaml", "name: v\nobjects:\n  - {name: a, category: ball, instance: v1, " + kModel + "}\n");
  const auto nested =
      Write("variety_nested.yaml", "name: v\ntraining_variety: [" + other +
                                       "]\nobjects:\n  - {name: n1, category: cup, instance: n1, " + kModel + "}\n");
  const auto with = [](const std::string& name, const std::string& variety) {
    return Write(name, "name: s\ntraining_variety: " + variety +
                           "\nobjects:\n  - {name: a, category: ball, instance: a, " + kModel + "}\n");
  };
  std::string e = ErrorOf(with("tv1.yaml", "[" + other + "]"));
  EXPECT_NE(e.find("training_variety[0]': object 'v1' of '" + other + "' is a cup, not one of this set's categories"),
            std::string::npos)
      << e;
  e = ErrorOf(with("tv2.yaml", "[" + taken + "]"));
  EXPECT_NE(e.find("object name 'a' of '" + taken + "' is taken"), std::string::npos) << e;
  e = ErrorOf(with("tv3.yaml", "[" + nested + "]"));
  EXPECT_NE(e.find("names a training variety of its own"), std::string::npos) << e;
  const std::string self = sortcell_test::TestTempDir() + "tv_self.yaml";
  e = ErrorOf(Write("tv_self.yaml", "name: s\ntraining_variety: [" + self +
                                        "]\nobjects:\n  - {name: a, category: ball, instance: a, " + kModel + "}\n"));
  EXPECT_NE(e.find("names a training variety of its own"), std::string::npos) << e;
  e = ErrorOf(with("tv4.yaml", "[/nonexistent/balls.yaml]"));
  EXPECT_NE(e.find("tv4.yaml': key 'training_variety[0]': object set '/nonexistent/balls.yaml'"), std::string::npos)
      << e;
  e = ErrorOf(with("tv5.yaml", "balls.yaml"));
  EXPECT_NE(e.find("key 'training_variety': expected a non-empty list of object set files, found 'balls.yaml'"),
            std::string::npos)
      << e;
}

TEST(ObjectSet, FindNamesTheSetAndTheObject) {
  const auto set = sortcell::files::LoadObjectSet(SORTCELL_SOURCE_DIR "/scenes/objects/paper.yaml");
  try {
    set.Find("teapot");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("paper.yaml': no object named 'teapot'"), std::string::npos) << e.what();
  }
}

TEST(OutputDir, WriteJsonNamesTheFileItCannotWrite) {
  try {
    sortcell::files::WriteJson("/nonexistent/dir/x.json", {{"a", 1}});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'/nonexistent/dir/x.json'"), std::string::npos) << e.what();
  }
}

}  // namespace
