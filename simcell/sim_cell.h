#pragma once
/// @file
/// The simulated sorting cell behind cell::CellIo: the Kinect renders the MuJoCo scene into an
/// organized cloud, the arm and gripper run under the robot layer's controller (ArmExecutor), time is
/// simulated time. What the policy receives is sensor data only; the capture's ground-truth label
/// image stays here, for the scorer (last_labels()).

#include <random>

#include <opencv2/core/mat.hpp>

#include "simcell/arm_executor.h"
#include "cell/cell_io.h"
#include "sim/kinect_camera.h"
#include "sim/kinect_noise.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {

class SimCell : public cell::CellIo {
 public:
  /// `kinect` may be null for a cell that never captures (the scripted pick); `noise` null renders
  /// ideal depth. `rng` drives the noise; `video` (optional) records every physics step.
  SimCell(const sim::Model& model, sim::Data& data, sim::KinectCamera* kinect, const sim::KinectNoiseParams* noise,
          std::mt19937_64* rng, sim::VideoRecorder* video, double control_period);

  /// @throws std::logic_error for a cell made without a camera.
  perception::Cloud::Ptr Capture() override;
  robot::Joints ReadJoints() const override { return exec_.JointPositions(); }
  robot::Joints CommandedJoints() const override { return exec_.ReferenceJoints(); }
  robot::GripperSensors ReadGripper() const override { return exec_.Gripper(); }
  cell::MotionResult Follow(std::string_view phase, const robot::JointTrajectory& trajectory) override;
  void CommandFingers(double left_half_gap, double right_half_gap) override;
  cell::MotionResult HoldUntil(std::string_view phase, double max_seconds, const std::function<bool()>& done) override;
  cell::MotionResult Wait(std::string_view phase, double seconds) override;
  double Now() const override { return exec_.time(); }

  /// Puts the arm at q and the fingers at `half_gap`, at rest, held there from now on.
  void Reset(const robot::Joints& q, double half_gap) { exec_.Reset(q, half_gap); }
  const robot::TrackingStats& tracking() const { return exec_.tracking(); }

  /// Ground truth of the last capture (scoring only): CV_16UC1, 0 = no object, i = the Kinect's
  /// object_names()[i - 1].
  const cv::Mat& last_labels() const { return last_labels_; }
  int frames() const { return frames_; }
  /// Wall time of the captures: render, noise, labels and the organized cloud (s).
  double render_wall_s() const { return render_wall_s_; }
  /// Wall time of turning the captures into organized clouds (s).
  double cloud_wall_s() const { return cloud_wall_s_; }
  /// Wall time of the physics steps (s).
  double step_wall_s() const { return exec_.step_wall_s(); }
  const ArmExecutor& executor() const { return exec_; }

 private:
  cell::MotionResult Result(const sim::StepStatus& status) const;

  ArmExecutor exec_;
  sim::KinectCamera* kinect_;
  const sim::KinectNoiseParams* noise_;
  std::mt19937_64* rng_;
  const sim::Data& data_;
  cv::Mat last_labels_;
  int frames_ = 0;
  double render_wall_s_ = 0;
  double cloud_wall_s_ = 0;
};

}  // namespace sortcell::simcell
