#include "app/sweep/sweep_spec.h"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <utility>

#include "common/seeding.h"
#include "files/yaml_reader.h"
#include "simcell/episode.h"
#include "sim/clutter_placement.h"

namespace sortcell::app {
namespace {

const std::set<std::string> kTopLevelKeys{"scene",    "cell",  "object_set", "unknown_set",       "model", "seed",
                                          "episodes", "seeds", "mode",       "episode_timeout_s", "axes"};
const std::set<std::string> kPathKeys{"scene", "cell", "object_set", "unknown_set", "model"};

// Reads the spec's keys: files are relative to the spec's folder and must exist.
class SpecReader {
 public:
  explicit SpecReader(const std::filesystem::path& file)
      : yaml_("sweep spec", file), base_(std::filesystem::absolute(file).parent_path()) {}

  const files::YamlReader& yaml() const { return yaml_; }

  std::filesystem::path File(const std::string& key, const std::string& value) const {
    const std::filesystem::path p = (base_ / value).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) yaml_.Fail("key '" + key + "': file '" + p.string() + "' not found");
    return p;
  }

 private:
  files::YamlReader yaml_;
  std::filesystem::path base_;
};

// ---- --set KEY=VALUE ----

std::string OverrideKeysText() {
  std::string keys;
  for (const auto& key : kTopLevelKeys) {
    if (key != "axes") keys += key + ", ";
  }
  std::string axes;
  for (const auto& name : SweepAxisNames()) axes += (axes.empty() ? "" : ", ") + name;
  return keys + "or axes.NAME with NAME one of " + axes;
}

// A path given on the command line is relative to the working folder, not to the spec.
void MakePathsAbsolute(YAML::Node& node) {
  if (node.IsScalar() && !node.Scalar().empty()) {
    node = std::filesystem::absolute(node.Scalar()).lexically_normal().string();
  } else if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      YAML::Node item = node[i];
      MakePathsAbsolute(item);
    }
  }
}

// "axes.NAME": the axis's values (one value: a fixed value).
void OverrideAxis(YAML::Node& root, const std::string& name, YAML::Node value) {
  const std::vector<std::string>& names = SweepAxisNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw std::invalid_argument("--set: unknown sweep spec key 'axes." + name + "' (expected " + OverrideKeysText() +
                                ")");
  }
  if (name == "model") MakePathsAbsolute(value);
  // (yaml-cpp: assigning one Node to another rebinds shared nodes, so new nodes are built, not assigned.)
  YAML::Node list(YAML::NodeType::Sequence);
  list.push_back(value);
  const YAML::Node values = value.IsScalar() ? list : value;
  const YAML::Node existing = std::as_const(root)["axes"];
  if (existing && !existing.IsMap() && !existing.IsNull()) return;  // The loader names the bad 'axes'.
  YAML::Node axes = existing && existing.IsMap() ? existing : YAML::Node(YAML::NodeType::Map);
  axes[name] = values;
  root["axes"] = axes;
}

// One KEY=VALUE onto the spec's YAML; VALUE is YAML (a number, a word, [a, b], {min: a, max: b}).
void ApplyOverride(YAML::Node& root, const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set: expected KEY=VALUE, found '" + text + "'");
  const std::string key = text.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(text.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("--set " + key + ": the value is not valid YAML: " + e.msg);
  }
  if (key.rfind("axes.", 0) == 0) return OverrideAxis(root, key.substr(5), value);
  if (!kTopLevelKeys.count(key) || key == "axes") {
    throw std::invalid_argument("--set: unknown sweep spec key '" + key + "' (expected " + OverrideKeysText() + ")");
  }
  if (kPathKeys.count(key)) MakePathsAbsolute(value);
  // One of 'episodes' and 'seeds' replaces the other.
  if (key == "episodes") root.remove("seeds");
  if (key == "seeds") root.remove("episodes");
  root[key] = value;
}

// ---- the keys ----

void ReadFiles(const SpecReader& r, const YAML::Node& root, SweepSpec& spec) {
  const files::YamlReader& y = r.yaml();
  spec.scene = r.File("scene", y.String(root, "scene", "the top level"));
  spec.object_set = r.File("object_set", y.String(root, "object_set", "the top level"));
  if (root["model"] && !root["model"].IsNull()) spec.model = r.File("model", y.String(root, "model", "the top level"));
  if (root["cell"]) spec.cell = r.File("cell", y.String(root, "cell", "the top level"));
  if (root["unknown_set"]) spec.unknown_set = r.File("unknown_set", y.String(root, "unknown_set", "the top level"));
}

void ReadEpisodes(const files::YamlReader& y, const YAML::Node& root, SweepSpec& spec) {
  if (root["seed"]) spec.seed = static_cast<uint64_t>(y.Integer(root["seed"], "seed"));
  if (root["episodes"] && root["seeds"]) y.Fail("give either 'episodes' or 'seeds', not both");
  if (root["episodes"]) {
    spec.episodes = static_cast<int>(y.Integer(root["episodes"], "episodes"));
    if (spec.episodes < 1 || spec.episodes > 1000000) y.Fail("key 'episodes': expected 1..1000000");
  }
  if (root["seeds"]) {
    const YAML::Node seeds = root["seeds"];
    if (!seeds.IsSequence() || seeds.size() == 0)
      y.Fail("key 'seeds': expected a non-empty list, found " + files::NodeKind(seeds));
    for (size_t i = 0; i < seeds.size(); ++i) {
      spec.seeds.push_back(static_cast<uint64_t>(y.Integer(seeds[i], "seeds[" + std::to_string(i) + "]")));
    }
  }
}

void ReadRunSettings(const files::YamlReader& y, const YAML::Node& root, SweepSpec& spec) {
  if (root["mode"]) {
    const std::string mode = y.String(root, "mode", "the top level");
    if (mode != "random" && mode != "grid") y.Fail("key 'mode': expected random or grid, found '" + mode + "'");
    spec.grid = mode == "grid";
  }
  if (root["episode_timeout_s"]) {
    spec.episode_timeout_s = y.Number(root["episode_timeout_s"], "episode_timeout_s");
    if (!(spec.episode_timeout_s > 0)) y.Fail("key 'episode_timeout_s': expected > 0");
  }
}

// A value of an axis whose values are an enum's spellings (`names`).
template <typename E, size_t N>
std::string NamedAxisValue(const files::YamlReader& y, const EnumNames<E, N>& names, const YAML::Node& v,
                           const std::string& where) {
  if (!v.IsScalar() || !FindName(names, v.Scalar())) {
    y.Fail("key '" + where + "': expected " + ExpectedNames(names) + ", found " +
           (v.IsScalar() ? "'" + v.Scalar() + "'" : files::NodeKind(v)));
  }
  return v.Scalar();
}

// One value of axis `name` (key `where` for messages): a model file, an object count, a noise seed, or a number
// (a scale > 0; a camera shift or turn >= 0).
nlohmann::json AxisValue(const SpecReader& r, const std::string& name, const YAML::Node& v, const std::string& where) {
  const files::YamlReader& y = r.yaml();
  if (name == "model") {
    if (!v.IsScalar() || v.Scalar().empty())
      y.Fail("key '" + where + "': expected a model file, found " + files::NodeKind(v));
    return r.File(where, v.Scalar()).string();
  }
  if (name == "placement") return NamedAxisValue(y, sim::kPlacementModeNames, v, where);
  if (name == "self_calibrate") return NamedAxisValue(y, simcell::kSelfCalibrationNames, v, where);
  if (name == "objects" || name == "unknown_objects" || name == "noise_seed") {
    const long long k = y.Integer(v, where);
    if (name == "objects" && k < 1) y.Fail("key '" + where + "': expected at least 1 object");
    return k;
  }
  const double x = y.Number(v, where);
  if (name == "lying_fraction" || name == "colour_jitter" || name == "reject_below") {
    if (!(x >= 0 && x <= 1)) y.Fail("key '" + where + "': expected a fraction in [0, 1]");
    return x;
  }
  const bool scale = name != "camera_shift_m" && name != "camera_turn_rad";
  if (scale ? !(x > 0) : !(x >= 0)) y.Fail("key '" + where + "': expected a value " + (scale ? "> 0" : ">= 0"));
  return x;
}

SweepAxis ReadAxis(const SpecReader& r, const std::string& name, const YAML::Node& node) {
  const files::YamlReader& y = r.yaml();
  SweepAxis axis;
  axis.name = name;
  const std::string key = "axes." + name;
  if (node.IsSequence()) {
    if (node.size() == 0) y.Fail("key '" + key + "': expected at least one value");
    for (size_t i = 0; i < node.size(); ++i)
      axis.values.push_back(AxisValue(r, name, node[i], key + "[" + std::to_string(i) + "]"));
  } else if (node.IsMap()) {
    y.RejectUnknownKeys(node, key, {"min", "max"});
    if (name == "model") y.Fail("key '" + key + "': models are a list of files, not a range");
    if (name == "placement") y.Fail("key '" + key + "': placements are a list of modes, not a range");
    if (name == "self_calibrate") {
      y.Fail("key '" + key + "': self_calibrate is a list of " + ExpectedNames(simcell::kSelfCalibrationNames) +
             ", not a range");
    }
    if (!node["min"] || !node["max"]) y.Fail("key '" + key + "': a range needs min and max");
    axis.min = AxisValue(r, name, node["min"], key + ".min").get<double>();
    axis.max = AxisValue(r, name, node["max"], key + ".max").get<double>();
    if (axis.max < axis.min) y.Fail("key '" + key + "': max is below min");
  } else {
    y.Fail("key '" + key + "': expected a list of values or {min, max}, found " + files::NodeKind(node));
  }
  return axis;
}

void ReadAxes(const SpecReader& r, const YAML::Node& root, SweepSpec& spec) {
  const YAML::Node axes = root["axes"];
  if (!axes || axes.IsNull()) return;
  if (!axes.IsMap()) r.yaml().Fail("key 'axes': expected a map of axis names, found " + files::NodeKind(axes));
  const std::vector<std::string>& names = SweepAxisNames();
  r.yaml().RejectUnknownKeys(axes, "axes", std::set<std::string>(names.begin(), names.end()));
  for (const auto& item : axes) spec.axes.push_back(ReadAxis(r, item.first.as<std::string>(), item.second));
}

}  // namespace

const std::vector<std::string>& SweepAxisNames() {
  static const std::vector<std::string> names{"objects",       "light_intensity", "camera_shift_m", "camera_turn_rad",
                                              "noise_scale",   "friction_scale",  "mass_scale",     "model",
                                              "reject_below",  "placement",       "lying_fraction", "self_calibrate",
                                              "colour_jitter", "unknown_objects", "noise_seed"};
  return names;
}

int SweepSpec::EpisodeCount() const {
  const int repeats = seeds.empty() ? episodes : static_cast<int>(seeds.size());
  if (!grid) return repeats;
  int cells = 1;
  for (const auto& axis : axes) cells *= axis.is_range() ? 1 : static_cast<int>(axis.values.size());
  return cells * repeats;
}

namespace {

// A value drawn from a range axis.
nlohmann::json DrawFromRange(const SweepAxis& axis, std::mt19937_64& rng) {
  if (axis.name == "objects" || axis.name == "unknown_objects" || axis.name == "noise_seed") {
    return std::uniform_int_distribution<int>(static_cast<int>(axis.min), static_cast<int>(axis.max))(rng);
  }
  return std::uniform_real_distribution<double>(axis.min, axis.max)(rng);
}

}  // namespace

std::pair<uint64_t, nlohmann::json> SweepSpec::Episode(int index) const {
  const int repeats = seeds.empty() ? episodes : static_cast<int>(seeds.size());
  nlohmann::json values = nlohmann::json::object();
  int repeat = index;
  if (grid) {
    // Grid cell = index / repeats (first axis slowest); every cell sees the same seeds and the same
    // values drawn from range axes (by repeat), so cells differ only in their listed axis values.
    repeat = index % repeats;
    int cell = index / repeats;
    std::mt19937_64 rng = EpisodeRng(seed, 0x5eed0000ULL + static_cast<uint64_t>(repeat));
    for (const auto& axis : axes) {
      if (axis.is_range()) values[axis.name] = DrawFromRange(axis, rng);
    }
    for (auto axis = axes.rbegin(); axis != axes.rend(); ++axis) {
      if (axis->is_range()) continue;
      const int n = static_cast<int>(axis->values.size());
      values[axis->name] = axis->values[cell % n];
      cell /= n;
    }
  } else {
    std::mt19937_64 rng = EpisodeRng(seed, 0x5eed0000ULL + static_cast<uint64_t>(index));
    for (const auto& axis : axes) {
      if (!axis.is_range()) {
        values[axis.name] = axis.values[std::uniform_int_distribution<size_t>(0, axis.values.size() - 1)(rng)];
      } else {
        values[axis.name] = DrawFromRange(axis, rng);
      }
    }
  }
  const uint64_t episode_seed = seeds.empty() ? seed + static_cast<uint64_t>(repeat) : seeds[repeat];
  return {episode_seed, values};
}

SweepSpec LoadSweepSpec(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  const SpecReader reader(file);
  YAML::Node loaded = reader.yaml().LoadMap("scene, object_set and axes");
  for (const auto& text : overrides) ApplyOverride(loaded, text);
  const YAML::Node& root = loaded;  // Read only from here (const lookups add no keys).
  reader.yaml().RejectUnknownKeys(root, "the top level", kTopLevelKeys);
  SweepSpec spec;
  spec.source = file;
  ReadFiles(reader, root, spec);
  ReadEpisodes(reader.yaml(), root, spec);
  ReadRunSettings(reader.yaml(), root, spec);
  ReadAxes(reader, root, spec);
  const bool unknowns =
      std::any_of(spec.axes.begin(), spec.axes.end(), [](const SweepAxis& a) { return a.name == "unknown_objects"; });
  if (unknowns && spec.unknown_set.empty()) reader.yaml().Fail("axis 'unknown_objects' needs the key 'unknown_set'");
  if (!unknowns && !spec.unknown_set.empty()) reader.yaml().Fail("key 'unknown_set' needs the axis 'unknown_objects'");
  return spec;
}

}  // namespace sortcell::app
