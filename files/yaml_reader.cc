#include "files/yaml_reader.h"

#include <cmath>
#include <stdexcept>

namespace sortcell::files {

std::string NodeKind(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Null:
      return "nothing";
    default:
      return "an undefined value";
  }
}

YAML::Node YamlReader::LoadMap(const std::string& expected_keys) const {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file_, ec)) Fail("file not found");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file_.string());
  } catch (const YAML::Exception& e) {
    Fail("not valid YAML: " + e.msg + " at line " + std::to_string(e.mark.line + 1));
  }
  if (!root.IsMap()) Fail("expected a map with keys " + expected_keys + ", found " + NodeKind(root));
  return root;
}

void YamlReader::Fail(const std::string& what) const {
  throw std::invalid_argument(kind_ + " '" + file_.string() + "': " + what);
}

void YamlReader::RejectUnknownKeys(const YAML::Node& map, const std::string& where,
                                   const std::set<std::string>& allowed) const {
  for (const auto& item : map) {
    // YAML allows a map or a list as a key ("? - a"); none of ours is one.
    if (!item.first.IsScalar()) Fail("a key in " + where + " is " + NodeKind(item.first) + ", expected a name");
    const std::string key = item.first.Scalar();
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      Fail("unknown key '" + key + "' in " + where + " (expected " + list + ")");
    }
  }
}

std::string YamlReader::String(const YAML::Node& map, const std::string& key, const std::string& where) const {
  const YAML::Node value = map[key];
  if (!value) Fail("missing key '" + key + "' in " + where);
  if (!value.IsScalar() || value.Scalar().empty()) {
    Fail("key '" + (where == "the top level" ? key : where + "." + key) + "': expected a non-empty string, found " +
         NodeKind(value));
  }
  return value.Scalar();
}

double YamlReader::Number(const YAML::Node& node, const std::string& name) const {
  if (node.IsScalar()) {
    try {
      size_t used = 0;
      const double v = std::stod(node.Scalar(), &used);
      if (used == node.Scalar().size() && std::isfinite(v)) return v;
    } catch (const std::logic_error&) {
    }
  }
  Fail("key '" + name + "': expected a number, found " + NodeKind(node));
}

long long YamlReader::Integer(const YAML::Node& node, const std::string& name) const {
  if (node.IsScalar() && !node.Scalar().empty() && node.Scalar().find_first_not_of("0123456789") == std::string::npos &&
      node.Scalar().size() < 19) {
    return std::stoll(node.Scalar());
  }
  Fail("key '" + name + "': expected a non-negative integer, found " + NodeKind(node));
}

}  // namespace sortcell::files
