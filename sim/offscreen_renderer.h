#pragma once
/// @file
/// Off-screen OpenGL rendering of a MuJoCo model through OSMesa (no display, no GPU).

#include <opencv2/core/mat.hpp>

#include <memory>
#include <string>

#include "sim/model.h"

namespace sortcell::sim {

/// Visual options shared by every sensor render: geom groups 0-2 (collision-only hulls in group 3
/// stay hidden, as in MuJoCo's viewer), no sites, frames, lights or camera glyphs.
struct RenderView {
  int camera_id = -1;  ///< A fixed camera of the model.
  int width = 640;
  int height = 480;
  /// Shadows (a depth pass per shadow-casting light) and the floor's reflection (the scene drawn
  /// twice): on for the Kinect, whose images the recognition model was trained on.
  bool shadows = true;
  bool reflections = true;
};

/// Lighting variation applied to every light of the scene (headlight included) at render time,
/// leaving the model untouched: datasets randomise it per capture.
struct Lighting {
  double intensity = 1.0;             ///< Scales ambient, diffuse and specular.
  double tilt_x = 0.0, tilt_y = 0.0;  ///< Added to each light direction's x and y before normalising.
};

/// The most textures MuJoCo 2.2.2's renderer draws per context (measured: the 101st and later render
/// white; about 400 crash).
inline constexpr int kMaxTextures = 100;

/// Renders a model's fixed cameras to colour, the raw depth buffer and segment ids. The OSMesa
/// context is created once per process and shared; each renderer owns its model's GPU resources.
class OffscreenRenderer {
 public:
  /// @throws std::runtime_error if no OSMesa context can be created; std::invalid_argument naming the
  ///         scene if it holds more than kMaxTextures textures.
  explicit OffscreenRenderer(const Model& model);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Colour (CV_8UC3, RGB order, top row first) and the raw depth buffer (CV_32FC1 in [0, 1], top
  /// row first; 1 where nothing was drawn).
  /// @throws std::invalid_argument naming the model's <visual><global offwidth/offheight> if the view
  ///         is larger than the off-screen buffer, or the camera id is not a camera of the model.
  void Render(const Data& data, const RenderView& view, cv::Mat& rgb, cv::Mat& depth_buffer);

  /// Colour only, no depth read back (review video).
  void RenderRgb(const Data& data, const RenderView& view, cv::Mat& rgb);

  /// Per-pixel geom id (CV_32SC1, top row first), -1 where no geom is seen: MuJoCo's
  /// segmentation render (mjRND_SEGMENT + mjRND_IDCOLOR), decoded through the scene's segids.
  void RenderGeomIds(const Data& data, const RenderView& view, cv::Mat& geom_ids);

  /// Lighting for the following colour renders.
  void SetLighting(const Lighting& lighting);

  /// @throws std::invalid_argument naming the model's <visual><global offwidth/offheight> if a
  ///         width x height view does not fit the off-screen buffer.
  void CheckViewSize(int width, int height) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sortcell::sim
