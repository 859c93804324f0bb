// `sortcell objects check`: a set of a user's objects is imported, dropped and reported; a bad object
// is one line naming its file and exit 2.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "../assets/user_objects.h"
#include "run_sortcell.h"
#include "temp_dir.h"

namespace {

using sortcell_test::RunSortcell;

using sortcell_test::SetWith;

TEST(ObjectsCheckCli, ABadObjectIsOneLineNamingItsFileAndExit2) {
  sortcell_test::TempDir dir;
  const auto user = sortcell_test::WriteUserObject(dir.path() / "user", "-1");
  const std::string set = SetWith(dir.path(), user.urdf.string());
  ::setenv("SORTCELL_IMPORT_CACHE", (dir.path() / "cache").c_str(), 1);
  const auto r = RunSortcell("objects check " + set + " --out " + (dir.path() / "out").string());
  ::unsetenv("SORTCELL_IMPORT_CACHE");  // Later tests of this process (a shard) must not see a removed folder.
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("object set '" + set + "'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(user.urdf.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mass"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

}  // namespace
