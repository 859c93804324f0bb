#pragma once
// What every fuzz target shares: the input written to a file where the reader expects one, and the
// check that a refused input was refused the way the CLI needs (one std::exception whose message names
// the file, so `sortcell` prints a one-line error and exits 2). Anything else is a finding: a crash or
// sanitizer report, a hang or a memory blow-up (libFuzzer's -timeout and -rss_limit_mb), a message
// that does not name the file, or an exception that is not a std::exception.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace sortcell_fuzz {

/// This process's scratch folder (mkdtemp under TMPDIR on first use), removed at exit.
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "sortcell_fuzz_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror("sortcell fuzz: mkdtemp");
      std::abort();
    }
    static const std::filesystem::path made = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(made, ignored);
    });
    return made;
  }();
  return dir;
}

/// Writes `size` bytes at `file` (its folders made).
inline void WriteInput(const std::filesystem::path& file, const uint8_t* data, size_t size) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) {
    std::fprintf(stderr, "sortcell fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
}

/// Links `name` in `dir` to the source tree's `name` (the folders a reader resolves relative paths in).
inline void LinkFromSource(const std::filesystem::path& dir, const std::string& name) {
  const std::filesystem::path link = dir / name;
  std::error_code ignored;
  if (std::filesystem::exists(std::filesystem::symlink_status(link, ignored))) return;
  std::filesystem::create_directories(link.parent_path());
  std::filesystem::create_symlink(std::filesystem::path(SORTCELL_SOURCE_DIR) / name, link);
}

/// Runs `read` on the input; a refusal must be a std::exception whose message names `culprit` by its
/// path (or, when given, `option`: the command-line option whose value was refused).
template <typename Read>
void ExpectReadOrRefusal(const std::filesystem::path& culprit, Read&& read, const std::string& option = "") {
  try {
    read();
  } catch (const std::exception& e) {
    const std::string what = e.what();
    const bool named =
        what.find(culprit.string()) != std::string::npos || (!option.empty() && what.find(option) != std::string::npos);
    if (!named) {
      std::fprintf(stderr, "sortcell fuzz: the refusal does not name '%s': %s\n", culprit.c_str(), what.c_str());
      std::abort();
    }
  }
}

/// Splits a fuzz input at the first `separator` line into two parts (a folder of two files); no
/// separator: all of it is the first part.
inline std::pair<std::string, std::string> SplitAt(const uint8_t* data, size_t size, const std::string& separator) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t at = text.find(separator);
  if (at == std::string::npos) return {text, ""};
  return {text.substr(0, at), text.substr(at + separator.size())};
}

}  // namespace sortcell_fuzz
