#pragma once
/// @file
/// Reading YAML configuration files (object sets, sweep specs) into plain structs with one-line
/// errors that name the file and the key: "<kind> '<file>': <what>".

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <string>

namespace sortcell::files {

/// "a map", "a list", "'text'" or "nothing", for messages.
std::string NodeKind(const YAML::Node& node);

class YamlReader {
 public:
  /// `kind` names the file's role in messages, e.g. "object set".
  YamlReader(std::string kind, std::filesystem::path file) : kind_(std::move(kind)), file_(std::move(file)) {}

  /// Loads the file; it must hold a map. @throws std::invalid_argument if missing, not YAML or not a map.
  YAML::Node LoadMap(const std::string& expected_keys) const;

  [[noreturn]] void Fail(const std::string& what) const;
  void RejectUnknownKeys(const YAML::Node& map, const std::string& where, const std::set<std::string>& allowed) const;
  /// A required non-empty string.
  std::string String(const YAML::Node& map, const std::string& key, const std::string& where) const;
  /// A number (key `name` for messages).
  double Number(const YAML::Node& node, const std::string& name) const;
  /// A non-negative integer.
  long long Integer(const YAML::Node& node, const std::string& name) const;

  const std::filesystem::path& file() const { return file_; }

 private:
  std::string kind_;
  std::filesystem::path file_;
};

}  // namespace sortcell::files
