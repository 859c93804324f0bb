#pragma once
/// @file
/// The synthetic Kinect v1: one fixed camera of the scene rendered off-screen to registered colour
/// and depth, with the Kinect noise model; a ground-truth label image and pose, for scoring, on request.

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include <random>
#include <string>
#include <vector>

#include "sim/camera_model.h"
#include "sim/kinect_noise.h"
#include "sim/model.h"
#include "sim/offscreen_renderer.h"

namespace sortcell::sim {

/// One capture, as the sensor gives it: colour and depth registered (same pinhole, same pixel grid).
struct KinectFrame {
  cv::Mat rgb;    ///< CV_8UC3, RGB order, top row first.
  cv::Mat depth;  ///< CV_32FC1, planar depth in metres, NaN where the sensor gives none.
  CameraIntrinsics intrinsics;
};

/// What the simulator knows of the same capture and the sensor does not give: for scoring, training
/// labels and tests only, handed out through its own channel (KinectCamera::Capture's `truth`).
struct FrameTruth {
  cv::Mat labels;                                          ///< CV_16UC1: 0 = no object, i = object_names()[i - 1].
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();  ///< Where the optical frame C truly is.
};

/// Wall time of the stages of every capture so far (s), for profiles.
struct CaptureTimings {
  double render_s = 0;  ///< Colour and depth render, read back, depth linearised.
  double noise_s = 0;   ///< The Kinect noise model.
  double labels_s = 0;  ///< The ground-truth label render (only with `truth`).
};

class KinectCamera {
 public:
  /// @throws std::invalid_argument naming the scene if it has no camera `camera_name` or its
  ///         off-screen buffer is smaller than width x height.
  explicit KinectCamera(const Model& model, const std::string& camera_name = "kinect", int width = 640,
                        int height = 480);

  /// Renders the current state. With `noise` null the depth is ideal (NaN only where nothing was
  /// drawn) and the colour the clean render; otherwise the Kinect noise model is applied to the depth
  /// and its colour model (`noise->colour`) to the colour image, driven by `rng`. With `truth`, the label
  /// image is rendered too and the camera's true pose given there.
  /// @throws std::invalid_argument if `noise` is given without `rng`.
  KinectFrame Capture(const Data& data, const KinectNoiseParams* noise, std::mt19937_64* rng,
                      FrameTruth* truth = nullptr);

  /// Capture in two steps, for a caller that renders the next scene while another thread applies the
  /// sensor's noise to this one: RenderClean renders (on the thread that made the camera: its GL
  /// context's), ApplySensorModel needs no GL and touches no camera. ApplySensorModel(RenderClean(data,
  /// truth), noise, rng) is Capture(data, &noise, &rng, truth), draw for draw.
  KinectFrame RenderClean(const Data& data, FrameTruth* truth = nullptr);
  static KinectFrame ApplySensorModel(KinectFrame clean, const KinectNoiseParams& noise, std::mt19937_64& rng);

  /// Lighting of the following captures (default: the scene's own).
  void SetLighting(const Lighting& lighting) { renderer_.SetLighting(lighting); }

  /// Names of the objects the label image numbers (the scene's free bodies, in body order).
  const std::vector<std::string>& object_names() const { return object_names_; }
  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  const CaptureTimings& timings() const { return timings_; }

 private:
  const Model& model_;
  int camera_id_;
  CameraIntrinsics intrinsics_;
  OffscreenRenderer renderer_;
  std::vector<std::string> object_names_;
  std::vector<uint16_t> geom_label_;  // Per geom: the label of the object it belongs to, or 0.
  CaptureTimings timings_;
};

}  // namespace sortcell::sim
