#pragma once
/// @file
/// Physical and sensor variations of a scene for sweeps: the objects' friction and mass, and a
/// displaced camera. Applied to a freshly loaded model, before any Data is made from it.

#include <random>
#include <string>

#include "sim/model.h"

namespace sortcell::sim {

struct SceneVariation {
  double friction_scale = 1.0;  ///< Multiplies the sliding friction of every object (free body) geom.
  double mass_scale = 1.0;      ///< Multiplies every object's mass and inertia.
  /// The camera is moved by this distance (m) in a random direction and turned by this angle (rad)
  /// about a random axis: a calibration error, since the robot keeps the nominal camera pose.
  double camera_shift_m = 0.0;
  double camera_turn_rad = 0.0;
  std::string camera = "kinect";
};

/// @throws std::invalid_argument naming the scene for non-positive scales, negative jitter or an
///         unknown camera.
void ApplyVariation(Model& model, const SceneVariation& variation, std::mt19937_64& rng);

}  // namespace sortcell::sim
