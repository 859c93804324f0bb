// The `sortcell` executable's contract: one-line errors and exit code 2 for bad input.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/app/run_sortcell.h"
#include "source_tree.h"

namespace {

using sortcell_test::ExpectOneLineError;
using sortcell_test::kCell;
using sortcell_test::RunSortcell;
using sortcell_test::TestTempDir;

TEST(Cli, HelpExitsZeroAndNamesCapture) {
  EXPECT_EQ(RunSortcell("--help").exit_code, 0);
  EXPECT_EQ(RunSortcell("capture --help").exit_code, 0);
}

TEST(Cli, VersionExitsZeroAndNamesTheProjectsVersion) {
  const auto version = RunSortcell("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, "sortcell " SORTCELL_VERSION "\n");
}

TEST(Cli, BadArgumentsExitTwoWithOneLine) {
  ExpectOneLineError(RunSortcell(""), "subcommand");
  ExpectOneLineError(RunSortcell("teleport"), "teleport");
  ExpectOneLineError(RunSortcell("capture --out " + TestTempDir() + "x"), "--scene");
  ExpectOneLineError(RunSortcell("capture --scene " + kCell + " --seed -3 --out " + TestTempDir() + "x"), "--seed");
  ExpectOneLineError(RunSortcell("capture --scene " + kCell + " --seed abc --out " + TestTempDir() + "x"), "--seed");
}

TEST(Cli, BadScenesExitTwoNamingTheFile) {
  const std::string out = TestTempDir() + "cli_bad_scene";
  ExpectOneLineError(RunSortcell("capture --scene /nonexistent/cell.xml --out " + out), "/nonexistent/cell.xml");
  const std::string malformed = TestTempDir() + "cli_malformed.xml";
  std::ofstream(malformed) << "<mujoco><worldbody><body></worldbody>";
  ExpectOneLineError(RunSortcell("capture --scene " + malformed + " --out " + out), malformed);
  const std::string no_camera = TestTempDir() + "cli_no_camera.xml";
  std::ofstream(no_camera) << "<mujoco><worldbody><geom type=\"plane\" size=\"1 1 1\"/></worldbody></mujoco>";
  ExpectOneLineError(RunSortcell("capture --scene " + no_camera + " --out " + out), "no camera named 'kinect'");
}

TEST(Cli, UnwritableOutputFolderExitsTwo) {
  const std::string file = TestTempDir() + "cli_a_file";
  std::ofstream(file) << "x";
  ExpectOneLineError(RunSortcell("capture --scene " + kCell + " --out " + file + "/sub"), "output folder");
  ExpectOneLineError(RunSortcell("capture --scene " + kCell + " --out " + file), "not a folder");
}

}  // namespace
