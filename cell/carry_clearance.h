#pragma once
/// @file
/// How low a held object may be carried to its bin: over what the camera saw on the table and in the
/// bins, checked sample by sample along the planned carry. A lift only as high as the scene needs is
/// time the cycle saves without holding the object any harder (the lift and the lowering into the bin
/// are the holding lines, the slowest of the cycle).

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "cell/arm_view.h"
#include "robot/joint_trajectory.h"

namespace sortcell::cell {

/// What a held object passes over on its way to a bin (world frame, m): the objects left on the table
/// as discs up to their tops, each bin as its outline up to its walls or what stands in it.
struct CarryObstacles {
  struct Disc {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    double radius = 0;
    double top_z = 0;
  };
  struct Box {
    Eigen::Vector2d min_xy = Eigen::Vector2d::Zero(), max_xy = Eigen::Vector2d::Zero();
    double top_z = 0;
  };
  std::vector<Disc> discs;
  std::vector<Box> boxes;
};

/// The least height (m) of what hangs from the TCP above the top of an obstacle it comes over, along
/// every sample of `trajectory`. Each of `parts` (the held object, the fingers, the palm) has
/// its lowest point below_tcp along the TCP's z (which points down; negative: above the TCP) and
/// comes over an obstacle where its reach (its radius, widened by `beside`) overlaps the obstacle's
/// outline. Samples with the TCP within kOnPlumbLine of one of `plumb_xy` are not counted: straight up
/// from where an object stood or down to where it is let go, nothing is passed over (what stands beside
/// it is the grasp's and the bin slot's to keep clear). +infinity when nothing comes over anything.
double LeastClearanceOver(const robot::JointTrajectory& trajectory, const std::vector<HeldObject>& parts,
                          const CarryObstacles& obstacles, double beside,
                          const std::vector<Eigen::Vector2d>& plumb_xy = {});

/// How far (m) from a plumb line's xy a sample still counts as on it: the lines' IK to well under a
/// millimetre, a blend's first sideways millimetres.
inline constexpr double kOnPlumbLine = 0.002;

}  // namespace sortcell::cell
