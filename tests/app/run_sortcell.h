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
  std::string out;
};

// Runs the binary with `args`, capturing stderr and stdout.
inline Result RunSortcell(const std::string& args) {
  // One file per test and call, in this process's own folder.
  static int call = 0;
  const std::string stem = TestTempDir() + "sortcell_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                           std::to_string(++call);
  const std::string command =
      std::string(SORTCELL_BINARY) + " " + args + " > " + stem + "_stdout.txt 2> " + stem + "_stderr.txt";
  const int status = std::system(command.c_str());
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(stem + "_stderr.txt"), out(stem + "_stdout.txt");
  r.err.assign(std::istreambuf_iterator<char>(err), {});
  r.out.assign(std::istreambuf_iterator<char>(out), {});
  return r;
}

inline void ExpectOneLineError(const Result& r, const std::string& needle) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
}

}  // namespace sortcell_test
