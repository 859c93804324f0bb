#include "simcell/episode_setup.h"

#include <algorithm>
#include <regex>
#include <set>
#include <stdexcept>

#include "files/data_dir.h"
#include "files/output_dir.h"
#include "simcell/sim_layout.h"
#include "sim/scene_composer.h"

namespace sortcell::simcell {
namespace {

constexpr int kDefaultMaxObjects = 6;

// Whether `scene` includes every one of `fragments` (its <include file="..."> elements, relative to
// its folder): a scene file's own objects, without compiling it.
bool IncludesAll(const std::filesystem::path& scene, const std::vector<std::filesystem::path>& fragments) {
  const std::string text = files::ReadTextFile(scene);
  static const std::regex kInclude(R"re(<include\s+file\s*=\s*"([^"]+)")re");
  std::set<std::filesystem::path> included;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kInclude); it != std::sregex_iterator(); ++it) {
    included.insert(std::filesystem::weakly_canonical(scene.parent_path() / (*it)[1].str()));
  }
  return std::all_of(fragments.begin(), fragments.end(), [&](const std::filesystem::path& f) {
    return included.count(std::filesystem::weakly_canonical(f)) > 0;
  });
}

}  // namespace

sim::Model LoadEpisodeScene(const std::filesystem::path& scene, const files::ObjectSet& set,
                            const files::CellFile& cell) {
  const std::filesystem::path data = files::DataDir();
  std::error_code ec;
  const bool default_cell = std::filesystem::equivalent(scene, data / "scenes" / "cell.xml", ec);
  std::vector<std::filesystem::path> fragments;
  for (const auto& o : set.objects) fragments.push_back(o.model);
  // The default cell holding another set is composed straight away, not loaded first to find that out.
  if (default_cell && !IncludesAll(scene, fragments)) {
    return sim::LoadComposedCell(data / "models", fragments, scene.string() + " with " + set.source.string(), {},
                                 files::BinsXml(cell));
  }
  sim::Model model = LoadCellScene(scene, cell);
  std::string missing;
  for (const auto& o : set.objects) {
    if (mj_name2id(model.get(), mjOBJ_BODY, o.name.c_str()) < 0)
      missing += (missing.empty() ? "'" : ", '") + o.name + "'";
  }
  if (!missing.empty()) {
    throw std::invalid_argument("scene '" + scene.string() + "': no object " + missing + " of object set '" +
                                set.source.string() + "' (the default cell, scenes/cell.xml, takes any set)");
  }
  return model;
}

files::ObjectSet LoadUnknownSet(const EpisodeOptions& options, const files::ObjectSet& set) {
  if (options.unknown_objects < 0) throw std::invalid_argument("--unknown-objects: expected >= 0");
  if (options.unknown_objects == 0) return {};
  if (options.unknown_set.empty()) throw std::invalid_argument("--unknown-objects: needs --unknown-set");
  files::ObjectSet unknown = files::LoadObjectSet(options.unknown_set);
  if (options.unknown_objects > static_cast<int>(unknown.objects.size())) {
    throw std::invalid_argument("--unknown-objects: expected at most " + std::to_string(unknown.objects.size()) +
                                " (the objects of set '" + options.unknown_set.string() + "'), got " +
                                std::to_string(options.unknown_objects));
  }
  for (const auto& spec : unknown.objects) {
    for (const auto& known : set.objects) {
      if (spec.name == known.name) {
        throw std::invalid_argument("--unknown-set '" + options.unknown_set.string() + "': object '" + spec.name +
                                    "' is also in set '" + set.source.string() + "'");
      }
    }
  }
  return unknown;
}

files::ObjectSet WithUnknown(const files::ObjectSet& set, const files::ObjectSet& unknown) {
  files::ObjectSet all = set;
  all.objects.insert(all.objects.end(), unknown.objects.begin(), unknown.objects.end());
  return all;
}

std::vector<files::ObjectSpec> ChooseUnknownObjects(const files::ObjectSet& unknown, int count, std::mt19937_64& rng) {
  if (count <= 0) return {};
  std::vector<files::ObjectSpec> all = unknown.objects;
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(count);
  return all;
}

int ObjectCount(const files::ObjectSet& set, const EpisodeOptions& options) {
  const int n = static_cast<int>(set.objects.size());
  const int count = options.objects > 0 ? options.objects : std::min(n, kDefaultMaxObjects);
  if (count < 1 || count > n) {
    throw std::invalid_argument("--objects: expected 1.." + std::to_string(n) + " (the objects of set '" +
                                set.source.string() + "'), got " + std::to_string(options.objects));
  }
  return count;
}

std::vector<files::ObjectSpec> ChooseObjects(const files::ObjectSet& set, const EpisodeOptions& options,
                                             std::mt19937_64& rng) {
  const int count = ObjectCount(set, options);
  if (static_cast<int>(options.placements.size()) > count) {
    throw std::invalid_argument("--place: " + std::to_string(options.placements.size()) + " placements for " +
                                std::to_string(count) + " objects");
  }
  std::vector<files::ObjectSpec> chosen;
  std::set<std::string> names;
  for (const auto& p : options.placements) {
    if (!names.insert(p.name).second) throw std::invalid_argument("--place: object '" + p.name + "' placed twice");
    chosen.push_back(set.Find(p.name));
  }
  std::vector<files::ObjectSpec> others;
  for (const auto& spec : set.objects) {
    if (!names.count(spec.name)) others.push_back(spec);
  }
  std::shuffle(others.begin(), others.end(), rng);
  for (int i = 0; static_cast<int>(chosen.size()) < count; ++i) chosen.push_back(others[i]);
  return chosen;
}

std::optional<std::vector<sim::TablePose>> TryDrawPoses(const std::vector<ObjectPlacement>& placements,
                                                        const std::vector<sim::ObjectShape>& shapes,
                                                        const sim::PlacementArea& area,
                                                        const sim::PlacementOptions& placement, std::mt19937_64& rng) {
  std::vector<sim::TablePose> fixed;
  for (size_t i = 0; i < placements.size(); ++i) {
    const ObjectPlacement& p = placements[i];
    if (p.lying && !shapes[i].lying) {
      throw std::invalid_argument("--place: object '" + p.name +
                                  "' cannot lie on its side (not taller than it is narrow)");
    }
    fixed.push_back({p.x, p.y, p.yaw, p.lying});
  }
  return sim::SampleClutter(shapes, fixed, area, placement, rng);
}

std::vector<sim::TablePose> DrawPoses(const std::vector<ObjectPlacement>& placements,
                                      const std::vector<sim::ObjectShape>& shapes, const sim::PlacementArea& area,
                                      const sim::PlacementOptions& placement, std::mt19937_64& rng) {
  if (auto poses = TryDrawPoses(placements, shapes, area, placement, rng)) return *poses;
  throw std::invalid_argument("--objects: " + std::to_string(shapes.size()) + " objects do not fit the table area (" +
                              sim::ToString(placement.mode) + " placement) with the given placements");
}

}  // namespace sortcell::simcell
