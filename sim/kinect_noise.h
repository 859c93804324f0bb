#pragma once
/// @file
/// Kinect v1 depth noise (DESIGN.md section 5): what a structured-light sensor does to an ideal
/// planar depth image. The parameters also carry the colour camera's model (sim/kinect_colour.h),
/// which KinectCamera applies to the colour image of a noisy capture.

#include <opencv2/core/mat.hpp>

#include <random>
#include <string>

#include "sim/camera_model.h"
#include "sim/kinect_colour.h"

namespace sortcell::sim {

/// Parameters of the noise model. Defaults are the Kinect v1 figures.
struct KinectNoiseParams {
  double min_range_m = 0.5;  ///< Closer than this: no depth.
  double max_range_m = 4.0;  ///< Farther than this: no depth.
  /// Axial sigma_z = a + b (z - c)^2 (Nguyen, Izadi, Lovell 2012), plus
  /// steep_gain / sqrt(z) * theta^2 / (pi/2 - theta)^2 beyond steep_angle.
  double axial_a_m = 0.0012;
  double axial_b_per_m = 0.0019;
  double axial_c_m = 0.4;
  double steep_gain = 0.0001;
  double steep_angle_rad = 60.0 * M_PI / 180.0;
  /// Lateral sigma_L = lateral_a_px + lateral_b_px * theta / (pi/2 - theta), in pixels.
  double lateral_a_px = 0.8;
  double lateral_b_px = 0.035;
  /// Disparity quantisation: 1/subpixel px with the IR camera's focal length and the baseline.
  bool quantize = true;
  double ir_focal_px = 580.0;
  double baseline_m = 0.075;
  double subpixel = 8.0;
  /// Dropouts: grazing incidence loses depth with a probability rising linearly from 0 at
  /// grazing_start to 1 at grazing_end; projector shadows next to depth edges lose it always.
  double grazing_start_rad = 70.0 * M_PI / 180.0;
  double grazing_end_rad = 80.0 * M_PI / 180.0;
  bool shadows = true;
  /// Multiplies both noise sigmas (sweeps vary it; 1 = the Kinect).
  double noise_scale = 1.0;
  /// The PrimeSense chip matches the projected pattern over a window of pixels, so each depth is the
  /// window's mean disparity over the same surface (neighbours within window_surface_m in depth): small
  /// round objects come out flatter towards the camera. Measured on real views of a 6 cm ball
  /// (../shared/real/rgbd-object, ball_2): the mean of CVFH's viewpoint block was bin 114.8 of 128,
  /// against 106 for simulated balls without the window and 113.5 with a 9 px one. On in the cell's captures
  /// and in its models' training captures alike (docs/cell.md: what it did to the sweeps). 0 or 1 = off.
  int correlation_window_px = 9;
  double window_surface_m = 0.02;
  /// The colour camera: exposure, white balance, saturation, blur and noise as measured on real views.
  KinectColourParams colour;
};

/// Which numbers the noise draws for given parameters and generator state: raised when that changes, so
/// that a model trained on captures of another draw is trained again (its digest holds ToString's line).
/// 2: every pixel's draws made at once by OpenCV's generator (1: std::normal_distribution pixel by pixel).
inline constexpr int kKinectNoiseDraws = 2;

/// The parameters in one line (with kKinectNoiseDraws), for records and digests of what a capture was rendered
/// through.
std::string ToString(const KinectNoiseParams& params);

/// Axial standard deviation (m) at depth z (m) and incidence angle theta (rad).
double AxialSigma(const KinectNoiseParams& params, double z, double theta);

/// Depth step (m) of the disparity quantisation at depth z.
double QuantizationStep(const KinectNoiseParams& params, double z);

/// The depth as the correlation window sees it: each finite pixel the mean disparity of the pixels of
/// its `window` x `window` neighbourhood within `surface_m` of its depth (NaN stays NaN). Exposed for tests.
cv::Mat CorrelationWindowDepth(const cv::Mat& depth, int window, double surface_m);

/// Returns the noisy depth (CV_32FC1, metres, NaN where the sensor gives no depth) for an ideal
/// planar depth image (CV_32FC1, NaN = nothing there) seen through intrinsics `k`. Steps: the
/// correlation window (when on); incidence angles from the clean surface; projector shadows (the projector sits
/// baseline_m to the camera's +x, so shadows fall to the left of foreground edges, ~ f b (1/z_fg - 1/z_bg) px wide);
/// lateral jitter; range and grazing dropouts; axial Gaussian noise; disparity quantisation. Deterministic for a given
/// rng state.
/// @throws std::invalid_argument if the image is not CV_32FC1 of k's size.
cv::Mat ApplyKinectNoise(const cv::Mat& ideal, const CameraIntrinsics& k, const KinectNoiseParams& p,
                         std::mt19937_64& rng);

/// Incidence angle (rad, 0 = facing the camera) per pixel from a planar depth image, NaN where the
/// surface normal cannot be estimated. Exposed for tests.
cv::Mat IncidenceAngles(const cv::Mat& depth, const CameraIntrinsics& k);

/// Pixels (CV_8UC1, 255 = shadowed) that the projector cannot light. Exposed for tests.
cv::Mat ProjectorShadowMask(const cv::Mat& depth, const CameraIntrinsics& k, double baseline_m);

}  // namespace sortcell::sim
