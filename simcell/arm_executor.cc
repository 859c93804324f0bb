#include "simcell/arm_executor.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sortcell::simcell {

ArmExecutor::ArmExecutor(const sim::Model& model, sim::Data& data, sim::VideoRecorder* video, double control_period)
    : model_(model), data_(data), video_(video), io_(model) {
  const double steps = control_period / model.get()->opt.timestep;
  substeps_ = static_cast<int>(std::lround(steps));
  if (substeps_ < 1 || std::abs(steps - substeps_) > 1e-9) {
    throw std::invalid_argument("control period " + std::to_string(control_period) +
                                " s is not a whole number of timesteps of scene '" + model.source() + "'");
  }
  sim::Vector6 qd;
  io_.ReadArm(data_, q_hold_, qd);
}

void ArmExecutor::Reset(const robot::Joints& q, double half_gap) {
  io_.SetArmPosition(data_, q);
  io_.SetGripperPosition(data_, half_gap);
  q_hold_ = q;
  mj_forward(model_.get(), data_.get());
}

sim::StepStatus ArmExecutor::ControlStep(const robot::Joints& q_ref, const robot::Joints& qd_ref,
                                         const robot::Joints& qdd_ref) {
  robot::Joints q, qd;
  io_.ReadArm(data_, q, qd);
  // Computed-torque feed-forward: gravity and Coriolis where the arm is, and the inertia of the
  // reference acceleration, so the feedback only corrects what the model does not know.
  const robot::Joints feed_forward = arm_model_.InverseDynamics(q, qd, qdd_ref);
  io_.SetArmTorques(data_, controller_.Torque(q, qd, q_ref, qd_ref, feed_forward));
  for (int i = 0; i < substeps_; ++i) {
    const auto start = std::chrono::steady_clock::now();
    sim::StepStatus status = sim::Step(model_, data_);
    step_wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++steps_;
    contacts_sum_ += data_->ncon;
    constraint_rows_sum_ += data_->nefc;
    if (video_) video_->Update(data_);
    if (status.code != sim::StepStatus::kOk) return status;
  }
  return {};
}

sim::StepStatus ArmExecutor::Follow(const robot::JointTrajectory& trajectory) {
  // One reference sample per control period: resample when the planner used another dt.
  const double period = substeps_ * model_.get()->opt.timestep;
  const int n = static_cast<int>(std::ceil(trajectory.duration() / period - 1e-9));
  for (int k = 1; k <= n; ++k) {
    const double t = std::fmin(k * period, trajectory.duration());
    const double u = t / trajectory.dt;
    const int i = std::min(static_cast<int>(u), trajectory.size() - 1);
    const int j = std::min(i + 1, trajectory.size() - 1);
    const double f = u - i;
    const robot::Joints q_ref = (1 - f) * trajectory.q[i] + f * trajectory.q[j];
    const robot::Joints qd_ref = (1 - f) * trajectory.qd[i] + f * trajectory.qd[j];
    const robot::Joints qdd_ref = (1 - f) * trajectory.qdd[i] + f * trajectory.qdd[j];
    sim::StepStatus status = ControlStep(q_ref, qd_ref, qdd_ref);
    if (status.code != sim::StepStatus::kOk) return status;
  }
  if (trajectory.size() > 0) q_hold_ = trajectory.q.back();
  return {};
}

sim::StepStatus ArmExecutor::Wait(double seconds) {
  const double period = substeps_ * model_.get()->opt.timestep;
  const int n = static_cast<int>(std::lround(seconds / period));
  for (int k = 0; k < n; ++k) {
    sim::StepStatus status = ControlStep(q_hold_, robot::Joints::Zero(), robot::Joints::Zero());
    if (status.code != sim::StepStatus::kOk) return status;
  }
  return {};
}

sim::StepStatus ArmExecutor::HoldUntil(double max_seconds, const std::function<bool()>& done) {
  const double start = data_->time;
  while (data_->time - start < max_seconds) {
    sim::StepStatus status = ControlStep(q_hold_, robot::Joints::Zero(), robot::Joints::Zero());
    if (status.code != sim::StepStatus::kOk) return status;
    if (done()) break;
  }
  return {};
}

void ArmExecutor::SetFingerTargets(double left_half_gap, double right_half_gap) {
  io_.SetFingerTargets(data_, left_half_gap, right_half_gap);
}

robot::Joints ArmExecutor::JointPositions() const {
  robot::Joints q, qd;
  io_.ReadArm(data_, q, qd);
  return q;
}

robot::GripperSensors ArmExecutor::Gripper() const { return io_.ReadGripper(data_); }

void ArmExecutor::SetPhase(const std::string& phase) {
  if (video_) video_->SetCaption(phase);
}

}  // namespace sortcell::simcell
