#pragma once
// Unique temporary folders for tests, never fixed names: two test runs on one machine (or two
// processes of one `ctest -j` run) never write into each other's files.
//  - TestTempDir(): this test process's folder, made with mkdtemp on first use. Use it where a test
//    used ::testing::TempDir(). ctest runs every test in its own process, so each test has its own.
//  - TempPath(name): a path in that folder.
//  - TempDir: a fresh folder inside it, for a test (or fixture) that wants one of its own.
// The process's folder is removed at exit when every test passed, and kept (named on stderr) for
// inspection when one failed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace sortcell_test {

namespace internal {

// mkdtemp of "<pattern>XXXXXX". @throws std::runtime_error if it cannot.
inline std::string MakeUniqueDir(const std::string& pattern) {
  std::vector<char> name(pattern.begin(), pattern.end());
  for (int i = 0; i < 6; ++i) name.push_back('X');
  name.push_back('\0');
  if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("cannot make a folder like '" + pattern + "XXXXXX'");
  return name.data();
}

inline std::string& ProcessDir() {
  static std::string dir;
  return dir;
}

inline void RemoveProcessDirIfAllPassed() {
  const std::string& dir = ProcessDir();
  if (dir.empty()) return;
  if (!::testing::UnitTest::GetInstance()->Passed()) {
    std::cerr << "test files kept in " << dir << "\n";
    return;
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace internal

/// This process's temporary folder, "<::testing::TempDir()>sortcell_test_XXXXXX/" (with the slash).
inline const std::string& TestTempDir() {
  std::string& dir = internal::ProcessDir();
  if (dir.empty()) {
    std::string base = ::testing::TempDir();
    if (base.empty() || base.back() != '/') base += '/';
    dir = internal::MakeUniqueDir(base + "sortcell_test_") + "/";
    std::atexit(internal::RemoveProcessDirIfAllPassed);
  }
  return dir;
}

/// "<TestTempDir()><name>": a path in this process's folder (not created).
inline std::string TempPath(const std::string& name) { return TestTempDir() + name; }

/// A fresh, empty folder "<TestTempDir()><prefix>_XXXXXX".
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "test") : path_(internal::MakeUniqueDir(TestTempDir() + prefix + "_")) {}

  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }
  /// A path inside the folder (not created).
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace sortcell_test
