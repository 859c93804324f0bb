#pragma once
// A fresh folder for a benchmark's outputs (mkdtemp under the system's temporary folder), so two
// runs on one machine never write into each other's files.
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

inline std::filesystem::path BenchTempDir(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a folder like '" + pattern + "'");
  return pattern;
}
