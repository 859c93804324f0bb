#include "files/object_set.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <vector>

#include <spdlog/spdlog.h>

#include "files/yaml_reader.h"

namespace sortcell::files {
namespace {

const std::set<std::string> kObjectKeys{"name", "category", "instance", "model", "urdf",
                                        "mesh", "mass",     "density",  "scale", "friction"};
const std::set<std::string> kImportKeys{"mass", "density", "scale", "friction"};

std::optional<double> PositiveNumber(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                                     const std::string& where) {
  if (!node[key]) return std::nullopt;
  const double value = reader.Number(node[key], where + "." + key);
  if (!std::isfinite(value) || value <= 0) {
    reader.Fail("key '" + where + "." + key + "': expected a positive number, found " + std::to_string(value));
  }
  return value;
}

void LogImport(const ObjectSpec& spec, const assets::ImportReport& r) {
  spdlog::info("imported '{}' from {}: {} convex collision piece(s), {:.3f} kg, {:.3f} x {:.3f} x {:.3f} m{}",
               spec.name, r.source, r.collision_pieces, r.mass, r.size.x(), r.size.y(), r.size.z(),
               r.texture.empty() ? "" : ", texture converted to PNG");
  for (const auto& w : r.warnings) spdlog::warn("'{}': {}", spec.name, w);
}

// An object given as `urdf` or `mesh`: imported into the cache; its model is the generated fragment.
void Import(const YamlReader& reader, const YAML::Node& node, const std::string& where,
            const std::filesystem::path& base, ObjectSpec& spec) {
  assets::ObjectSource source;
  source.name = spec.name;
  const std::string kind = node["urdf"] ? "urdf" : "mesh";
  const std::filesystem::path file = (base / reader.String(node, kind, where)).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    reader.Fail("key '" + where + "." + kind + "': file '" + file.string() + "' not found");
  (kind == "urdf" ? source.urdf : source.mesh) = file;
  source.mass = PositiveNumber(reader, node, "mass", where);
  source.density = PositiveNumber(reader, node, "density", where);
  source.scale = PositiveNumber(reader, node, "scale", where).value_or(1.0);
  source.friction = PositiveNumber(reader, node, "friction", where);
  if (kind == "mesh" && !source.mass && !source.density)
    reader.Fail("key '" + where + "': a mesh needs 'mass' or 'density'");
  assets::ImportedObject imported;
  try {
    imported = assets::ImportObject(source, ImportCacheDir());
  } catch (const std::invalid_argument& e) {
    reader.Fail("key '" + where + "." + kind + "': " + e.what());
  }
  spec.model = imported.fragment;
  spec.import = imported.report;
  if (!imported.from_cache) LogImport(spec, imported.report);
}

// `training_variety: [FILE, ...]`: the objects of those sets, each of one of `set`'s categories.
void LoadTrainingVariety(const YamlReader& reader, const YAML::Node& node, const std::filesystem::path& base,
                         ObjectSet& set) {
  if (!node.IsSequence() || node.size() == 0) {
    reader.Fail("key 'training_variety': expected a non-empty list of object set files, found " + NodeKind(node));
  }
  const std::vector<std::string> categories = set.Categories();
  std::set<std::string> names;
  for (const auto& o : set.objects) names.insert(o.name);
  for (size_t i = 0; i < node.size(); ++i) {
    const std::string where = "training_variety[" + std::to_string(i) + "]";
    if (!node[i].IsScalar() || node[i].Scalar().empty()) {
      reader.Fail("key '" + where + "': expected an object set file, found " + NodeKind(node[i]));
    }
    const std::filesystem::path file = (base / node[i].Scalar()).lexically_normal();
    // One level only, checked before loading it: a file naming itself must not recurse.
    ObjectSet variety;
    bool nested = false;
    try {
      nested = static_cast<bool>(YamlReader("object set", file).LoadMap("name and objects")["training_variety"]);
      if (!nested) variety = LoadObjectSet(file);
    } catch (const std::invalid_argument& e) {
      reader.Fail("key '" + where + "': " + e.what());
    }
    if (nested)
      reader.Fail("key '" + where + "': '" + file.string() + "' names a training variety of its own (one level only)");
    for (const ObjectSpec& o : variety.objects) {
      if (std::find(categories.begin(), categories.end(), o.category) == categories.end()) {
        reader.Fail("key '" + where + "': object '" + o.name + "' of '" + file.string() + "' is a " + o.category +
                    ", not one of this set's categories");
      }
      if (!names.insert(o.name).second) {
        reader.Fail("key '" + where + "': object name '" + o.name + "' of '" + file.string() + "' is taken");
      }
      set.training_variety.push_back(o);
    }
  }
}

}  // namespace

std::filesystem::path ImportCacheDir() {
  if (const char* env = std::getenv("SORTCELL_IMPORT_CACHE"); env && *env) return env;
#ifdef SORTCELL_DEFAULT_IMPORT_CACHE
  return SORTCELL_DEFAULT_IMPORT_CACHE;
#else
  return std::filesystem::path("out") / "imports";
#endif
}

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
  reader.RejectUnknownKeys(root, "the top level", {"name", "objects", "training_variety"});

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
    reader.RejectUnknownKeys(node, where, kObjectKeys);
    ObjectSpec spec;
    spec.name = reader.String(node, "name", where);
    spec.category = reader.String(node, "category", where);
    spec.instance = reader.String(node, "instance", where);
    if (!names.insert(spec.name).second) reader.Fail("duplicate object name '" + spec.name + "' at " + where);
    const int sources = (node["model"] ? 1 : 0) + (node["urdf"] ? 1 : 0) + (node["mesh"] ? 1 : 0);
    if (sources != 1) {
      reader.Fail("key '" + where + "': expected exactly one of 'model', 'urdf' or 'mesh', found " +
                  std::to_string(sources));
    }
    if (node["model"]) {
      for (const auto& key : kImportKeys) {
        if (node[key]) reader.Fail("key '" + where + "." + key + "': only for 'urdf' or 'mesh' objects");
      }
      spec.model = (base / reader.String(node, "model", where)).lexically_normal();
      if (!std::filesystem::is_regular_file(spec.model, ec)) {
        reader.Fail("key '" + where + ".model': file '" + spec.model.string() + "' not found");
      }
    } else {
      Import(reader, node, where, base, spec);
    }
    set.objects.push_back(std::move(spec));
  }
  if (root["training_variety"]) LoadTrainingVariety(reader, root["training_variety"], base, set);
  return set;
}

std::string ObjectModelsDigest(const ObjectSet& set, const std::filesystem::path& texture_dir) {
  std::string content;
  const auto append = [&content](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    content.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  // Labels too (they are what a model learns) and where each object belongs.
  for (const auto& object : set.objects) {
    content += "\nobject " + object.name + " " + object.category + " " + object.instance + "\n";
    append(object.model);
  }
  for (const auto& object : set.training_variety) {
    content += "\nvariety " + object.name + " " + object.category + " " + object.instance + "\n";
    append(object.model);
  }
  std::error_code ec;
  if (std::filesystem::is_directory(texture_dir, ec)) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(texture_dir)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) append(file);
  }
  return assets::ContentDigest(content);
}

}  // namespace sortcell::files
