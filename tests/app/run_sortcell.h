#pragma once
// Runs the `sortcell` executable for CLI tests.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "temp_dir.h"

namespace sortcell_test {

struct Result {
  int exit_code = -1;
  std::string err;
};

// Runs the binary with `args`, capturing stderr (stdout is discarded).
inline Result RunSortcell(const std::string& args) {
  // One file per test and call, in this process's own folder.
  static int call = 0;
  const std::string err_file = TestTempDir() + "sortcell_stderr_" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                               std::to_string(++call) + ".txt";
  const std::string command = std::string(SORTCELL_BINARY) + " " + args + " > /dev/null 2> " + err_file;
  const int status = std::system(command.c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  return r;
}

inline void ExpectOneLineError(const Result& r, const std::string& needle) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
}

}  // namespace sortcell_test
