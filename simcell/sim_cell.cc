#include "simcell/sim_cell.h"

#include <stdexcept>
#include <string>

#include "common/wall_clock.h"
#include "sim/point_cloud.h"

namespace sortcell::simcell {

SimCell::SimCell(const sim::Model& model, sim::Data& data, sim::KinectCamera* kinect,
                 const sim::KinectNoiseParams* noise, std::mt19937_64* rng, sim::VideoRecorder* video,
                 double control_period)
    : exec_(model, data, video, control_period), kinect_(kinect), noise_(noise), rng_(rng), data_(data) {}

perception::Cloud::Ptr SimCell::Capture() {
  if (kinect_ == nullptr) throw std::logic_error("SimCell::Capture: this cell has no camera");
  exec_.SetPhase("observe");
  const auto start = WallClock::now();
  sim::FrameTruth truth;
  const sim::KinectFrame frame = kinect_->Capture(data_, noise_, rng_, &truth);
  const auto cloud_start = WallClock::now();
  perception::Cloud::Ptr cloud = sim::ToOrganizedCloud(frame);
  cloud_wall_s_ += SecondsSince(cloud_start);
  render_wall_s_ += SecondsSince(start);
  ++frames_;
  last_labels_ = truth.labels;
  return cloud;
}

cell::MotionResult SimCell::Result(const sim::StepStatus& status) const {
  if (status.code == sim::StepStatus::kOk) return {};
  return {cell::MotionStatus::kFault, status.detail};
}

cell::MotionResult SimCell::Follow(std::string_view phase, const robot::JointTrajectory& trajectory) {
  exec_.SetPhase(std::string(phase));
  return Result(exec_.Follow(trajectory));
}

void SimCell::CommandFingers(double left_half_gap, double right_half_gap) {
  exec_.SetFingerTargets(left_half_gap, right_half_gap);
}

cell::MotionResult SimCell::HoldUntil(std::string_view phase, double max_seconds, const std::function<bool()>& done) {
  exec_.SetPhase(std::string(phase));
  return Result(exec_.HoldUntil(max_seconds, done));
}

cell::MotionResult SimCell::Wait(std::string_view phase, double seconds) {
  exec_.SetPhase(std::string(phase));
  return Result(exec_.Wait(seconds));
}

}  // namespace sortcell::simcell
