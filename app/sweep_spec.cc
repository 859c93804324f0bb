#include "app/sweep_spec.h"

#include <random>

#include "app/seeding.h"
#include "app/yaml_reader.h"

namespace sortcell::app {

const std::vector<std::string>& SweepAxisNames() {
  static const std::vector<std::string> names{"objects",     "light_intensity", "camera_shift_m", "camera_turn_rad",
                                               "noise_scale", "friction_scale",  "mass_scale",     "model"};
  return names;
}

int SweepSpec::EpisodeCount() const {
  const int repeats = seeds.empty() ? episodes : static_cast<int>(seeds.size());
  if (!grid) return repeats;
  int cells = 1;
  for (const auto& axis : axes) cells *= static_cast<int>(axis.values.size());
  return cells * repeats;
}

std::pair<uint64_t, nlohmann::json> SweepSpec::Episode(int index) const {
  const int repeats = seeds.empty() ? episodes : static_cast<int>(seeds.size());
  nlohmann::json values = nlohmann::json::object();
  int repeat = index;
  if (grid) {
    // Grid cell = index / repeats (first axis slowest); every cell sees the same seeds, so cells
    // differ only in their axis values.
    repeat = index % repeats;
    int cell = index / repeats;
    for (auto axis = axes.rbegin(); axis != axes.rend(); ++axis) {
      const int n = static_cast<int>(axis->values.size());
      values[axis->name] = axis->values[cell % n];
      cell /= n;
    }
  } else {
    std::mt19937_64 rng = EpisodeRng(seed, 0x5eed0000ULL + static_cast<uint64_t>(index));
    for (const auto& axis : axes) {
      if (!axis.is_range()) {
        values[axis.name] = axis.values[std::uniform_int_distribution<size_t>(0, axis.values.size() - 1)(rng)];
      } else if (axis.name == "objects") {
        values[axis.name] = std::uniform_int_distribution<int>(static_cast<int>(axis.min), static_cast<int>(axis.max))(rng);
      } else {
        values[axis.name] = std::uniform_real_distribution<double>(axis.min, axis.max)(rng);
      }
    }
  }
  const uint64_t episode_seed = seeds.empty() ? seed + static_cast<uint64_t>(repeat) : seeds[repeat];
  return {episode_seed, values};
}

SweepSpec LoadSweepSpec(const std::filesystem::path& file) {
  const YamlReader reader("sweep spec", file);
  const YAML::Node root = reader.LoadMap("scene, object_set and axes");
  reader.RejectUnknownKeys(root, "the top level",
                           {"scene", "object_set", "model", "seed", "episodes", "seeds", "mode", "episode_timeout_s", "axes"});
  SweepSpec spec;
  spec.source = file;
  const std::filesystem::path base = std::filesystem::absolute(file).parent_path();
  std::error_code ec;
  const auto path = [&](const std::string& key, const std::string& value) {
    const std::filesystem::path p = (base / value).lexically_normal();
    if (!std::filesystem::is_regular_file(p, ec)) reader.Fail("key '" + key + "': file '" + p.string() + "' not found");
    return p;
  };
  spec.scene = path("scene", reader.String(root, "scene", "the top level"));
  spec.object_set = path("object_set", reader.String(root, "object_set", "the top level"));
  if (root["model"] && !root["model"].IsNull()) spec.model = path("model", reader.String(root, "model", "the top level"));
  if (root["seed"]) spec.seed = static_cast<uint64_t>(reader.Integer(root["seed"], "seed"));
  if (root["episodes"] && root["seeds"]) reader.Fail("give either 'episodes' or 'seeds', not both");
  if (root["episodes"]) {
    spec.episodes = static_cast<int>(reader.Integer(root["episodes"], "episodes"));
    if (spec.episodes < 1 || spec.episodes > 1000000) reader.Fail("key 'episodes': expected 1..1000000");
  }
  if (root["seeds"]) {
    const YAML::Node seeds = root["seeds"];
    if (!seeds.IsSequence() || seeds.size() == 0) reader.Fail("key 'seeds': expected a non-empty list, found " + NodeKind(seeds));
    for (size_t i = 0; i < seeds.size(); ++i) {
      spec.seeds.push_back(static_cast<uint64_t>(reader.Integer(seeds[i], "seeds[" + std::to_string(i) + "]")));
    }
  }
  if (root["mode"]) {
    const std::string mode = reader.String(root, "mode", "the top level");
    if (mode != "random" && mode != "grid") reader.Fail("key 'mode': expected random or grid, found '" + mode + "'");
    spec.grid = mode == "grid";
  }
  if (root["episode_timeout_s"]) {
    spec.episode_timeout_s = reader.Number(root["episode_timeout_s"], "episode_timeout_s");
    if (!(spec.episode_timeout_s > 0)) reader.Fail("key 'episode_timeout_s': expected > 0");
  }
  const YAML::Node axes = root["axes"];
  if (axes && !axes.IsNull()) {
    if (!axes.IsMap()) reader.Fail("key 'axes': expected a map of axis names, found " + NodeKind(axes));
    const std::vector<std::string>& names = SweepAxisNames();
    reader.RejectUnknownKeys(axes, "axes", std::set<std::string>(names.begin(), names.end()));
    for (const auto& item : axes) {
      SweepAxis axis;
      axis.name = item.first.as<std::string>();
      const std::string key = "axes." + axis.name;
      const YAML::Node node = item.second;
      const auto value = [&](const YAML::Node& v, const std::string& where) -> nlohmann::json {
        if (axis.name == "model") {
          if (!v.IsScalar() || v.Scalar().empty()) reader.Fail("key '" + where + "': expected a model file, found " + NodeKind(v));
          return path(where, v.Scalar()).string();
        }
        if (axis.name == "objects") {
          const long long k = reader.Integer(v, where);
          if (k < 1) reader.Fail("key '" + where + "': expected at least 1 object");
          return k;
        }
        const double x = reader.Number(v, where);
        const bool scale = axis.name != "camera_shift_m" && axis.name != "camera_turn_rad";
        if (scale ? !(x > 0) : !(x >= 0)) reader.Fail("key '" + where + "': expected a value " + (scale ? "> 0" : ">= 0"));
        return x;
      };
      if (node.IsSequence()) {
        if (node.size() == 0) reader.Fail("key '" + key + "': expected at least one value");
        for (size_t i = 0; i < node.size(); ++i) axis.values.push_back(value(node[i], key + "[" + std::to_string(i) + "]"));
      } else if (node.IsMap()) {
        reader.RejectUnknownKeys(node, key, {"min", "max"});
        if (spec.grid) reader.Fail("key '" + key + "': a grid needs a list of values, not a range");
        if (axis.name == "model") reader.Fail("key '" + key + "': models are a list of files, not a range");
        if (!node["min"] || !node["max"]) reader.Fail("key '" + key + "': a range needs min and max");
        axis.min = value(node["min"], key + ".min").get<double>();
        axis.max = value(node["max"], key + ".max").get<double>();
        if (axis.max < axis.min) reader.Fail("key '" + key + "': max is below min");
      } else {
        reader.Fail("key '" + key + "': expected a list of values or {min, max}, found " + NodeKind(node));
      }
      spec.axes.push_back(std::move(axis));
    }
  }
  return spec;
}

}  // namespace sortcell::app
