#pragma once
/// @file
/// Kinect v1 colour: what its RGB camera does to the scene's colours next to a clean OpenGL render. Real
/// captures (the RGB-D Object Dataset's) are darker, bluer and less saturated, softer and grainier; a
/// recognition model trained on clean renders misnames them. The defaults are measured from the real
/// views in ../shared/real/rgbd-object (bench/kinect_colour_measure prints the measurement).

#include <opencv2/core/mat.hpp>

#include <random>
#include <string>

namespace sortcell::sim {

struct KinectColourParams {
  bool enabled = true;
  /// Gain on every channel: the sensor's exposure (a white surface's brightness, real over rendered).
  /// (Measured 0.83: the real turntable's white V 212 against the rendered plates' 255, which clip, so
  /// the render's white is at least that bright.)
  double exposure = 0.83;
  /// Per-channel gains (R, G, B) on top of the exposure, mean 1: the sensor's white balance (measured:
  /// the real white is bluer than the render's).
  double white_balance_r = 0.96, white_balance_g = 0.98, white_balance_b = 1.06;
  /// Chroma scale about each pixel's luma (1 = unchanged, 0 = grey); measured 0.74: the real banana's
  /// saturation (S 144) against the rendered lemons' (S 194).
  double saturation = 0.74;
  /// Optical and demosaicing blur (Gaussian sigma, pixels); measured 0.5: what gives the render the
  /// real views' sharpness.
  double blur_sigma_px = 0.5;
  /// Per-pixel, per-channel Gaussian noise (8-bit levels); measured 0: the real crops are smoother pixel
  /// to pixel (0.67 levels) than the textured renders already are (1.21), so none is added by default.
  double noise_sigma = 0.0;
};

/// The parameters in one line ("exposure 0.83, white balance 0.96 0.98 1.06, ..."): for records and
/// digests of what a capture was rendered through.
std::string ToString(const KinectColourParams& params);

/// The per-capture variation of training captures: exposure x U(0.6, 1.2) (real views of darker
/// objects and rooms are darker still, DESIGN.md section 5), saturation x U(0.85, 1.15), each
/// white-balance gain x U(0.96, 1.04), so a model does not learn one camera's exact colour.
KinectColourParams JitterColour(const KinectColourParams& params, std::mt19937_64& rng);

/// The Kinect's colour image of a clean render (CV_8UC3, RGB): white balance and exposure, saturation
/// (one linear map per pixel), blur, then noise, clipped to 8 bits. Deterministic for a given rng state;
/// the input is returned unchanged (a copy) when `params.enabled` is false.
/// @throws std::invalid_argument if the image is not CV_8UC3 or a parameter is negative or not finite
///         (the message names it and its value).
cv::Mat ApplyKinectColour(const cv::Mat& rgb, const KinectColourParams& params, std::mt19937_64& rng);

}  // namespace sortcell::sim
