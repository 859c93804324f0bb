#include "app/common/object_set.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/common/yaml_reader.h"

namespace sortcell::app {

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
  const YamlReader reader("object set", file);
  const YAML::Node root = reader.LoadMap("name and objects");
  std::error_code ec;
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

std::string ObjectModelsDigest(const ObjectSet& set, const std::filesystem::path& texture_dir) {
  std::string content;
  const auto append = [&content](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    content.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  for (const auto& object : set.objects) append(object.model);
  std::error_code ec;
  if (std::filesystem::is_directory(texture_dir, ec)) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(texture_dir)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) append(file);
  }
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << std::hash<std::string>{}(content);
  return hex.str();
}

}  // namespace sortcell::app
