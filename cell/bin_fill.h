#pragma once
/// @file
/// How full each bin is, as the robot knows it: the camera sees into the bins (they stand at the sides
/// of its view) and the robot remembers what it released where. A held object lowered onto one already
/// in the bin is pressed into it and flung out; the release point and height come from this instead.

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
  double clearance = 0;  ///< The object's bottom above the floor when let go (m).
  double yaw_offset = 0;  ///< First placement yaw (rad); with yaw_step the yaws tried.
  double yaw_step = 0;
  std::vector<int> slots;  ///< The layout's bin slots the object will take.
};

class BinFill {
 public:
  /// @throws std::invalid_argument if the layout has no bin slots.
  explicit BinFill(const CellLayout& layout);

  /// Raises each slot's height to what the capture shows in it (camera frame cloud, calibrated pose
  /// X_WC): the height above the floor of the highest few points inside the slot's square, within the
  /// bin's walls, leaving out points of the arm (`arm`, from the encoders at the capture). Never
  /// lowers a slot: what went into a bin stays there, and part of it may be hidden this time.
  void See(const perception::Cloud& cloud, const Eigen::Isometry3d& X_WC, const std::vector<Capsule>& arm);
  /// An object of `height` (m) was let go at `release`: its slots are at least that high now.
  void Released(const std::string& category, const BinRelease& release, double height);

  /// An upright object: the lowest slot (the layout's order from `filled` where they tie), let go
  /// `min_clearance` above the floor or that far above what is already there.
  /// @throws std::invalid_argument naming the category if the layout has no bin for it.
  BinRelease Upright(const std::string& category, int filled, double min_clearance) const;
  /// A lying object, longer than the bin is wide: along the lower of the two diagonals, in the middle,
  /// let go above the walls (lowered in, its ends would catch on them) and above what is there.
  BinRelease Lying(const std::string& category) const;

  /// Each slot's height above the bin floor (m), in the layout's slot order.
  const std::vector<double>& Heights(const std::string& category) const;

 private:
  const CellLayout& layout_;
  std::map<std::string, std::vector<double>> heights_;
};

}  // namespace sortcell::cell
