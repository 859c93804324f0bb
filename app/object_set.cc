#include "app/object_set.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <set>
#include <stdexcept>

namespace sortcell::app {
namespace {

std::string NodeKind(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
    case YAML::NodeType::Null: return "nothing";
    default: return "an undefined value";
  }
}

class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument("object set '" + file_.string() + "': " + what);
  }

  void RejectUnknownKeys(const YAML::Node& map, const std::string& where, const std::set<std::string>& allowed) const {
    for (const auto& item : map) {
      const std::string key = item.first.as<std::string>();
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        Fail("unknown key '" + key + "' in " + where + " (expected " + list + ")");
      }
    }
  }

  std::string String(const YAML::Node& map, const std::string& key, const std::string& where) const {
    const YAML::Node value = map[key];
    if (!value) Fail("missing key '" + key + "' in " + where);
    if (!value.IsScalar() || value.Scalar().empty()) {
      Fail("key '" + where + "." + key + "': expected a non-empty string, found " + NodeKind(value));
    }
    return value.Scalar();
  }

 private:
  std::filesystem::path file_;
};

}  // namespace

std::vector<std::string> ObjectSet::Categories() const {
  std::vector<std::string> categories;
  for (const auto& o : objects) {
    if (std::find(categories.begin(), categories.end(), o.category) == categories.end()) {
      categories.push_back(o.category);
    }
  }
  return categories;
}

const ObjectSpec& ObjectSet::Find(const std::string& name) const {
  for (const auto& o : objects) {
    if (o.name == name) return o;
  }
  throw std::invalid_argument("object set '" + source.string() + "': no object named '" + name + "'");
}

ObjectSet LoadObjectSet(const std::filesystem::path& file) {
  Reader reader(file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) reader.Fail("file not found");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    reader.Fail("not valid YAML: " + e.msg + " at line " + std::to_string(e.mark.line + 1));
  }
  if (!root.IsMap()) reader.Fail("expected a map with keys name and objects, found " + NodeKind(root));
  reader.RejectUnknownKeys(root, "the top level", {"name", "objects"});

  ObjectSet set;
  set.source = file;
  set.name = reader.String(root, "name", "the top level");
  const YAML::Node objects = root["objects"];
  if (!objects) reader.Fail("missing key 'objects'");
  if (!objects.IsSequence() || objects.size() == 0) {
    reader.Fail("key 'objects': expected a non-empty list, found " + NodeKind(objects));
  }
  const std::filesystem::path base = std::filesystem::absolute(file).parent_path();
  std::set<std::string> names;
  for (size_t i = 0; i < objects.size(); ++i) {
    const std::string where = "objects[" + std::to_string(i) + "]";
    const YAML::Node node = objects[i];
    if (!node.IsMap()) reader.Fail("key '" + where + "': expected a map, found " + NodeKind(node));
    reader.RejectUnknownKeys(node, where, {"name", "category", "instance", "model"});
    ObjectSpec spec;
    spec.name = reader.String(node, "name", where);
    spec.category = reader.String(node, "category", where);
    spec.instance = reader.String(node, "instance", where);
    spec.model = (base / reader.String(node, "model", where)).lexically_normal();
    if (!names.insert(spec.name).second) reader.Fail("duplicate object name '" + spec.name + "' at " + where);
    if (!std::filesystem::is_regular_file(spec.model, ec)) {
      reader.Fail("key '" + where + ".model': file '" + spec.model.string() + "' not found");
    }
    set.objects.push_back(std::move(spec));
  }
  return set;
}

}  // namespace sortcell::app
