#pragma once
/// @file
/// How full each bin is, as the robot knows it: the camera sees into the bins (they stand at the sides
/// of its view) and the robot remembers what it released where. A held object lowered onto one already
/// in the bin is pressed into it and flung out; the release point and height come from this instead.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cell/arm_view.h"
#include "cell/cell_layout.h"
#include "perception/cloud.h"

namespace sortcell::cell {

/// Where and how high to let go of an object in its bin.
struct BinRelease {
  Eigen::Vector3d p_W_floor = Eigen::Vector3d::Zero();  ///< Below the release point, on the bin's floor.
  double clearance = 0;                                 ///< The object's bottom above the floor when let go (m).
  double yaw_offset = 0;                                ///< First placement yaw (rad); with yaw_step the yaws tried.
  double yaw_step = 0;
  /// Where it will lie in the bin (bin frame: offsets from the floor centre, m): within half_width of
  /// the segment from..to, a disc around a slot for an upright object (from = to), the band along a
  /// diagonal for a lying one.
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  double half_width = 0;
};

/// A height map of each bin's inside, in cells of kBinCell (m): the height above the floor of what
/// is in each cell, as far as the robot knows.
class BinFill {
 public:
  explicit BinFill(const CellLayout& layout);

  /// Sets each cell the capture sees (camera frame cloud, calibrated pose X_WC) to what it shows there:
  /// the height above the floor of its third-highest point inside the bin's walls (0 where it sees
  /// the floor), leaving out points of the arm (`arm`, from the encoders at the capture). A cell it
  /// does not see (behind a wall or the arm) keeps what the robot knew of it.
  void See(const perception::Cloud& cloud, const Eigen::Isometry3d& X_WC, const CapsuleList& arm);
  /// An object of `height` (m) was let go at `release`: it rests on what is under its disc or band,
  /// and that is at least that much higher now.
  void Released(const std::string& bin, const BinRelease& release, double height);

  /// An upright object standing on a disc of `radius` (m): the layout's bin slot with the least
  /// under that disc (the layout's order from `filled` where they tie), let go `min_clearance` above
  /// the floor or that far above what is already there. Only slots `placeable` accepts are chosen
  /// (the arm can let this object go there); when it accepts none, the choice among all of them.
  /// @throws std::invalid_argument naming the bin if the layout has none of that name, or if the
  ///         layout has no bin slots.
  BinRelease Upright(const std::string& bin, int filled, double radius, double min_clearance,
                     const std::function<bool(const BinRelease&)>& placeable = {}) const;
  /// A lying object, longer than the bin is wide: along a diagonal, in the middle, let go above the
  /// walls (lowered in, its ends would catch on them) and above what is on the diagonals. Until a
  /// capture sees it, it may be anywhere in the bin.
  BinRelease Lying(const std::string& bin) const;

  /// The height (m) of the highest cell under `release`'s disc or band.
  double HighestUnder(const std::string& bin, const BinRelease& release) const;
  /// The height (m) of the highest cell of `bin`: what stands highest in it.
  double HighestIn(const std::string& bin) const;

 private:
  struct Map {
    Eigen::Vector2d half = Eigen::Vector2d::Zero();  // The bin's inner half extents (m).
    int nx = 0, ny = 0;                              // Cells along x and y.
    std::vector<double> height;                      // Row-major, nx x ny cells from the bin's (-x, -y) corner.
    Eigen::Vector2d CellCentre(int i, int j) const;
  };
  const Map& MapOf(const std::string& bin) const;
  bool Under(const BinRelease& release, const Eigen::Vector2d& p) const;

  const CellLayout& layout_;
  std::map<std::string, Map> maps_;
};

}  // namespace sortcell::cell
