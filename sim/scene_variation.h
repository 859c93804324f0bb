#pragma once
/// @file
/// Physical and sensor variations of a scene for sweeps: the objects' friction, mass and colours, and
/// a displaced camera. Applied to a freshly loaded model, before any Data is made from it.

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
  /// Each object's colours varied at random, as one batch of an object differs from the next (0: as
  /// modelled, 1: the most): hue by up to +-25 deg x colour_jitter, saturation and brightness by up to
  /// +-30 % x colour_jitter. A printed (textured) material varies in brightness only, and only darker
  /// (MuJoCo tints a texture by the material's colour, which cannot pass white).
  double colour_jitter = 0.0;
};

/// The colours are drawn from a stream of their own (seeded from a copy of `rng`), so `rng` draws and
/// is left the same at any colour jitter: a seed sets the same scene.
/// @throws std::invalid_argument naming the scene for non-positive scales, negative jitter, a colour
///         jitter outside [0, 1] or an unknown camera.
void ApplyVariation(Model& model, const SceneVariation& variation, std::mt19937_64& rng);

/// Every object's colours varied by one draw per object from `rng`, as ApplyVariation does for
/// colour_jitter (hue up to +-25 deg, saturation and value up to +-30 %, times `jitter`; a textured
/// material's brightness only). Changes the model's materials and geom colours in place.
/// @throws std::invalid_argument for a jitter outside [0, 1].
void JitterObjectColours(Model& model, double jitter, std::mt19937_64& rng);

}  // namespace sortcell::sim
