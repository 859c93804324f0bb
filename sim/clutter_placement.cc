#include "sim/clutter_placement.h"

#include <cmath>
#include <stdexcept>

namespace sortcell::sim {
namespace {

constexpr int kBisections = 30;      // Sliding an object against another: 2^-30 of the start distance.
constexpr double kTouching = 0.001;  // Footprints this much beyond the contact gap still touch (m).

// Whether an object is laid on its side: only one that can lie, with the options' chance (no draw at
// all when the fraction is 0, so scenes without lying objects draw as they always did).
bool DrawLying(const ObjectShape& shape, const PlacementOptions& options, std::uniform_real_distribution<double>& unit,
               std::mt19937_64& rng) {
  return shape.lying && options.lying_fraction > 0 && unit(rng) < options.lying_fraction;
}

struct Placed {
  std::vector<Eigen::Vector2d> outline;  // In the world.
  Eigen::Vector2d centre;
  double radius = 0;
  int group = 0;
};

class Arrangement {
 public:
  Arrangement(const PlacementArea& area, const PlacementOptions& options) : area_(area), options_(options) {}

  // Whether `outline` fits the area and keeps its distance from everything placed: touching its own
  // group (the contact gap), the area's gap from the others.
  bool Fits(const std::vector<Eigen::Vector2d>& outline, int group) const {
    for (const auto& v : outline) {
      if ((v.array() < area_.min.array()).any() || (v.array() > area_.max.array()).any()) return false;
    }
    return Clear(outline, group);
  }
  bool Clear(const std::vector<Eigen::Vector2d>& outline, int group) const {
    for (const Placed& p : placed_) {
      const double gap = p.group == group ? options_.contact_gap_m : area_.gap_m;
      if (Separation(outline, p.outline) < gap) return false;
    }
    return true;
  }
  // Whether `outline` touches a member of `group` (within a millimetre of the contact gap).
  bool Touches(const std::vector<Eigen::Vector2d>& outline, int group) const {
    for (const Placed& p : placed_) {
      if (p.group == group && Separation(outline, p.outline) < options_.contact_gap_m + kTouching) return true;
    }
    return false;
  }
  void Add(const RestingShape& shape, const TablePose& pose, int group) {
    const Eigen::Vector2d centre(pose.x, pose.y);
    placed_.push_back({PlacedOutline(shape.outline, centre, pose.yaw), centre, shape.radius, group});
  }
  // Indices of what is placed in `group`.
  std::vector<int> Members(int group) const {
    std::vector<int> members;
    for (size_t i = 0; i < placed_.size(); ++i) {
      if (placed_[i].group == group) members.push_back(static_cast<int>(i));
    }
    return members;
  }
  const Placed& at(int i) const { return placed_[i]; }

 private:
  const PlacementArea& area_;
  const PlacementOptions& options_;
  std::vector<Placed> placed_;
};

// Anywhere in the area.
std::optional<Eigen::Vector2d> DrawFree(const Arrangement& arrangement, const RestingShape& shape, double yaw,
                                        int group, const PlacementArea& area, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d span = (area.max - area.min).array() - 2 * shape.radius;
  // One draw per statement (arguments are evaluated in an unspecified order): y first, as GCC did.
  const double fraction_y = unit(rng);
  const double fraction_x = unit(rng);
  const Eigen::Vector2d c(area.min.x() + shape.radius + fraction_x * std::fmax(0.0, span.x()),
                          area.min.y() + shape.radius + fraction_y * std::fmax(0.0, span.y()));
  if (!arrangement.Fits(PlacedOutline(shape.outline, c, yaw), group)) return std::nullopt;
  return c;
}

// Against a member of its group: from that member's centre outwards in a random direction, slid in
// until it just clears everything.
std::optional<Eigen::Vector2d> DrawTouching(const Arrangement& arrangement, const std::vector<int>& members,
                                            const RestingShape& shape, double yaw, int group, const PlacementArea& area,
                                            std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Placed& base = arrangement.at(members[std::uniform_int_distribution<size_t>(0, members.size() - 1)(rng)]);
  const double angle = 2 * M_PI * unit(rng);
  const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
  const auto clear_at = [&](double t) {
    return arrangement.Clear(PlacedOutline(shape.outline, base.centre + t * direction, yaw), group);
  };
  double near = 0, far = base.radius + shape.radius + area.gap_m + 0.01;
  if (!clear_at(far)) return std::nullopt;
  for (int k = 0; k < kBisections; ++k) {
    const double mid = 0.5 * (near + far);
    (clear_at(mid) ? far : near) = mid;
  }
  const Eigen::Vector2d c = base.centre + far * direction;
  const std::vector<Eigen::Vector2d> outline = PlacedOutline(shape.outline, c, yaw);
  // Stopped by another group's gap before it met its own group: not touching, try again.
  if (!arrangement.Fits(outline, group) || !arrangement.Touches(outline, group)) return std::nullopt;
  return c;
}

// Which group each drawn object joins.
std::vector<int> Groups(int count, int fixed, PlacementMode mode, std::mt19937_64& rng) {
  std::vector<int> groups;
  if (mode == PlacementMode::kDense) {
    groups.assign(count, 0);
  } else {
    int group = fixed;
    for (const int size : ClusterSizes(count, rng)) {
      groups.insert(groups.end(), size, group++);
    }
  }
  return groups;
}

std::optional<std::vector<TablePose>> ArrangeOnce(const std::vector<ObjectShape>& shapes,
                                                  const std::vector<TablePose>& fixed, const PlacementArea& area,
                                                  const PlacementOptions& options, std::mt19937_64& rng,
                                                  int max_tries) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Arrangement arrangement(area, options);
  std::vector<TablePose> poses = fixed;
  const bool dense = options.mode == PlacementMode::kDense;
  for (size_t i = 0; i < fixed.size(); ++i) {
    const ObjectShape& s = shapes[i];
    arrangement.Add(s.Resting(fixed[i].lying), fixed[i], dense ? 0 : static_cast<int>(i));
  }
  const int drawn = static_cast<int>(shapes.size() - fixed.size());
  const std::vector<int> groups = Groups(drawn, static_cast<int>(fixed.size()), options.mode, rng);
  for (int k = 0; k < drawn; ++k) {
    const ObjectShape& shape = shapes[fixed.size() + k];
    TablePose pose;
    pose.lying = DrawLying(shape, options, unit, rng);
    const RestingShape& resting = shape.Resting(pose.lying);
    std::optional<Eigen::Vector2d> centre;
    for (int attempt = 0; attempt < max_tries && !centre; ++attempt) {
      pose.yaw = 2 * M_PI * unit(rng);
      const std::vector<int> members = arrangement.Members(groups[k]);
      centre = members.empty() ? DrawFree(arrangement, resting, pose.yaw, groups[k], area, rng)
                               : DrawTouching(arrangement, members, resting, pose.yaw, groups[k], area, rng);
    }
    if (!centre) return std::nullopt;
    pose.x = centre->x();
    pose.y = centre->y();
    arrangement.Add(resting, pose, groups[k]);
    poses.push_back(pose);
  }
  return poses;
}

// Sparse: discs (ObjectShape::disc_radius about the origin; lying, the disc about the outline's middle)
// the area's gap apart, drawn as today's scenes always were (SampleTablePoses) and redrawn where they
// meet a fixed one.
std::optional<std::vector<TablePose>> SampleSparse(const std::vector<ObjectShape>& shapes,
                                                   const std::vector<TablePose>& fixed, const PlacementArea& area,
                                                   const PlacementOptions& options, std::mt19937_64& rng,
                                                   int max_tries) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto radius = [&](size_t i, bool lying) {
    return lying ? shapes[i].lying->middle_radius : shapes[i].disc_radius;
  };
  // Where a lying object's disc is centred, from its origin.
  const auto middle = [&](size_t i, const TablePose& p) -> Eigen::Vector2d {
    return p.lying ? Eigen::Rotation2Dd(p.yaw) * shapes[i].lying->middle : Eigen::Vector2d::Zero();
  };
  for (int tries = 0; tries < kPlacementArrangements; ++tries) {
    // Which lie, drawn afresh for each arrangement: long lying objects may not fit together.
    std::vector<bool> lying;
    std::vector<double> radii;
    for (size_t i = fixed.size(); i < shapes.size(); ++i) {
      lying.push_back(DrawLying(shapes[i], options, unit, rng));
      radii.push_back(radius(i, lying.back()));
    }
    auto drawn = SampleTablePoses(radii, area, rng, max_tries);
    if (!drawn) {
      if (options.lying_fraction > 0) continue;
      return std::nullopt;
    }
    bool clear = true;
    for (size_t j = 0; j < drawn->size(); ++j) {  // Drawn: the discs' centres; the origins from them.
      TablePose& p = (*drawn)[j];
      p.lying = lying[j];
      const Eigen::Vector2d origin = Eigen::Vector2d(p.x, p.y) - middle(fixed.size() + j, p);
      p.x = origin.x();
      p.y = origin.y();
    }
    for (size_t i = 0; i < fixed.size() && clear; ++i) {
      const TablePose f{fixed[i].x, fixed[i].y, fixed[i].yaw, fixed[i].lying && shapes[i].lying.has_value()};
      const Eigen::Vector2d c_i = Eigen::Vector2d(f.x, f.y) + middle(i, f);
      for (size_t j = 0; j < drawn->size() && clear; ++j) {
        const TablePose& p = (*drawn)[j];
        const Eigen::Vector2d c_j = Eigen::Vector2d(p.x, p.y) + middle(fixed.size() + j, p);
        clear = (c_i - c_j).norm() >= radius(i, f.lying) + radii[j] + area.gap_m;
      }
    }
    if (!clear) continue;
    std::vector<TablePose> poses = fixed;
    poses.insert(poses.end(), drawn->begin(), drawn->end());
    return poses;
  }
  return std::nullopt;
}

}  // namespace

const char* ToString(PlacementMode mode) { return NameOf(kPlacementModeNames, mode); }

std::optional<PlacementMode> ParsePlacementMode(const std::string& text) { return FindName(kPlacementModeNames, text); }

std::vector<int> ClusterSizes(int count, std::mt19937_64& rng) {
  std::vector<int> sizes;
  int left = count;
  while (left > 0) {
    std::vector<int> allowed;  // 2-4, never leaving a lone object behind.
    for (int size = 2; size <= 4; ++size) {
      if (size <= left && left - size != 1) allowed.push_back(size);
    }
    const int size =
        allowed.empty() ? left : allowed[std::uniform_int_distribution<size_t>(0, allowed.size() - 1)(rng)];
    sizes.push_back(size);
    left -= size;
  }
  return sizes;
}

std::optional<std::vector<TablePose>> SampleClutter(const std::vector<ObjectShape>& shapes,
                                                    const std::vector<TablePose>& fixed, const PlacementArea& area,
                                                    const PlacementOptions& options, std::mt19937_64& rng,
                                                    int max_tries) {
  if (fixed.size() > shapes.size()) {
    throw std::invalid_argument("placement: " + std::to_string(fixed.size()) + " fixed poses for " +
                                std::to_string(shapes.size()) + " objects");
  }
  if (!(options.lying_fraction >= 0 && options.lying_fraction <= 1)) {
    throw std::invalid_argument("placement: lying fraction must be in [0, 1], got " +
                                std::to_string(options.lying_fraction));
  }
  if (options.mode == PlacementMode::kSparse) return SampleSparse(shapes, fixed, area, options, rng, max_tries);
  for (int arrangement = 0; arrangement < kPlacementArrangements; ++arrangement) {
    if (auto poses = ArrangeOnce(shapes, fixed, area, options, rng, max_tries)) return poses;
  }
  return std::nullopt;
}

}  // namespace sortcell::sim
