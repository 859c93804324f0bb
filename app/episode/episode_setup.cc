#include "app/episode/episode_setup.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace sortcell::app {
namespace {

constexpr int kDefaultMaxObjects = 6;

}  // namespace

int ObjectCount(const ObjectSet& set, const EpisodeOptions& options) {
  const int n = static_cast<int>(set.objects.size());
  const int count = options.objects > 0 ? options.objects : std::min(n, kDefaultMaxObjects);
  if (count < 1 || count > n) {
    throw std::invalid_argument("--objects: expected 1.." + std::to_string(n) + " (the objects of set '" +
                                set.source.string() + "'), got " + std::to_string(options.objects));
  }
  return count;
}

std::vector<ObjectSpec> ChooseObjects(const ObjectSet& set, const EpisodeOptions& options, std::mt19937_64& rng) {
  const int count = ObjectCount(set, options);
  if (static_cast<int>(options.placements.size()) > count) {
    throw std::invalid_argument("--place: " + std::to_string(options.placements.size()) +
                                " placements for " + std::to_string(count) + " objects");
  }
  std::vector<ObjectSpec> chosen;
  std::set<std::string> names;
  for (const auto& p : options.placements) {
    if (!names.insert(p.name).second) throw std::invalid_argument("--place: object '" + p.name + "' placed twice");
    chosen.push_back(set.Find(p.name));
  }
  std::vector<ObjectSpec> others;
  for (const auto& spec : set.objects) {
    if (!names.count(spec.name)) others.push_back(spec);
  }
  std::shuffle(others.begin(), others.end(), rng);
  for (int i = 0; static_cast<int>(chosen.size()) < count; ++i) chosen.push_back(others[i]);
  return chosen;
}

std::vector<sim::TablePose> DrawPoses(const std::vector<ObjectPlacement>& placements, const std::vector<double>& radii,
                                      const sim::PlacementArea& area, std::mt19937_64& rng) {
  std::vector<sim::TablePose> poses;
  for (const auto& p : placements) poses.push_back({p.x, p.y, p.yaw});
  const size_t fixed = poses.size();
  const std::vector<double> random_radii(radii.begin() + fixed, radii.end());
  for (int tries = 0; tries < 50; ++tries) {
    const auto drawn = sim::SampleTablePoses(random_radii, area, rng);
    if (!drawn) break;
    bool clear = true;
    for (size_t i = 0; i < fixed && clear; ++i) {
      for (size_t j = 0; j < drawn->size(); ++j) {
        const double d = std::hypot(poses[i].x - (*drawn)[j].x, poses[i].y - (*drawn)[j].y);
        if (d < radii[i] + random_radii[j] + area.gap_m) clear = false;
      }
    }
    if (clear) {
      poses.insert(poses.end(), drawn->begin(), drawn->end());
      return poses;
    }
  }
  throw std::invalid_argument("--objects: " + std::to_string(radii.size()) +
                              " objects do not fit the table area with the given placements");
}

}  // namespace sortcell::app
