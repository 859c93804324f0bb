#include "sim/arm_io.h"

#include <cmath>

namespace sortcell::sim {
namespace {

const char* const kJoints[6] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
const char* const kMotors[6] = {"shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"};
const char* const kFingerJoints[2] = {"finger_left_joint", "finger_right_joint"};
const char* const kFingerServos[2] = {"finger_left", "finger_right"};
const char* const kPads[4] = {"finger_left_pad_upper", "finger_left_pad_lower", "finger_right_pad_upper",
                              "finger_right_pad_lower"};

}  // namespace

ArmIo::ArmIo(const Model& model) : m_(model.get()) {
  for (int i = 0; i < 6; ++i) {
    const int joint = model.Id(mjOBJ_JOINT, kJoints[i]);
    qpos_[i] = m_->jnt_qposadr[joint];
    dof_[i] = m_->jnt_dofadr[joint];
    motor_[i] = model.Id(mjOBJ_ACTUATOR, kMotors[i]);
  }
  for (int i = 0; i < 2; ++i) {
    const int joint = model.Id(mjOBJ_JOINT, kFingerJoints[i]);
    finger_qpos_[i] = m_->jnt_qposadr[joint];
    finger_dof_[i] = m_->jnt_dofadr[joint];
    finger_servo_[i] = model.Id(mjOBJ_ACTUATOR, kFingerServos[i]);
  }
  for (int i = 0; i < 4; ++i) pads_[i] = model.Id(mjOBJ_GEOM, kPads[i]);
}

void ArmIo::ReadArm(const Data& data, Vector6& q, Vector6& qd) const {
  for (int i = 0; i < 6; ++i) {
    q[i] = data->qpos[qpos_[i]];
    qd[i] = data->qvel[dof_[i]];
  }
}

void ArmIo::SetArmTorques(Data& data, const Vector6& tau) const {
  for (int i = 0; i < 6; ++i) data->ctrl[motor_[i]] = tau[i];
}

void ArmIo::SetArmPosition(Data& data, const Vector6& q) const {
  for (int i = 0; i < 6; ++i) {
    data->qpos[qpos_[i]] = q[i];
    data->qvel[dof_[i]] = 0;
  }
}

void ArmIo::SetGripperTarget(Data& data, double half_gap) const {
  for (int i = 0; i < 2; ++i) data->ctrl[finger_servo_[i]] = half_gap;
}

void ArmIo::SetFingerTargets(Data& data, double left_half_gap, double right_half_gap) const {
  data->ctrl[finger_servo_[0]] = left_half_gap;
  data->ctrl[finger_servo_[1]] = right_half_gap;
}

void ArmIo::SetGripperPosition(Data& data, double half_gap) const {
  for (int i = 0; i < 2; ++i) {
    data->qpos[finger_qpos_[i]] = half_gap;
    data->qvel[finger_dof_[i]] = 0;
    data->ctrl[finger_servo_[i]] = half_gap;
  }
}

robot::GripperSensors ArmIo::ReadGripper(const Data& data) const {
  robot::GripperSensors r;
  r.left_half_gap = data->qpos[finger_qpos_[0]];
  r.right_half_gap = data->qpos[finger_qpos_[1]];
  r.left_speed = data->qvel[finger_dof_[0]];
  r.right_speed = data->qvel[finger_dof_[1]];
  for (int c = 0; c < data->ncon; ++c) {
    const mjContact& contact = data->contact[c];
    for (int p = 0; p < 4; ++p) {
      if (contact.geom1 != pads_[p] && contact.geom2 != pads_[p]) continue;
      mjtNum force[6];
      mj_contactForce(m_, data.get(), c, force);
      const bool left = p < 2;
      (left ? r.left_pad_force : r.right_pad_force) += force[0];
      (left ? r.left_pad_shear : r.right_pad_shear) += std::hypot(force[1], force[2]);
      (left ? r.left_pad_twist : r.right_pad_twist) += std::abs(force[3]);
      break;
    }
  }
  return r;
}

}  // namespace sortcell::sim
