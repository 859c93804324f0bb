#include "robot/ur5_dynamics.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "robot/gripper_geometry.h"
#include "robot/ur5_dh.h"

namespace sortcell::robot {
namespace {

constexpr double kGravity = 9.81;  // m/s^2, along -z of the Base frame

MassProperties Body(double mass, const Eigen::Vector3d& p_com, const Eigen::Vector3d& diagonal_inertia) {
  MassProperties body;
  body.mass = mass;
  body.p_com = p_com;
  body.inertia = diagonal_inertia.asDiagonal();
  return body;
}

// The UR5's moving links in their joint frames, as models/ur5/ur5.urdf gives them (ur5_urdf.h, generated
// from it at build time).
std::array<MassProperties, 6> Ur5Links() {
  std::array<MassProperties, 6> links;
  for (size_t i = 0; i < links.size(); ++i) {
    const auto& c = ur5_urdf::kLinkCom[i];
    const auto& inertia = ur5_urdf::kLinkInertia[i];
    links[i] = Body(ur5_urdf::kLinkMass[i], {c[0], c[1], c[2]}, {inertia[0], inertia[1], inertia[2]});
  }
  return links;
}

// The motors and gearboxes (models/ur5: the joints' armature, damping and frictionloss): reflected
// rotor inertia (kg m^2), viscous damping (N m s/rad) and Coulomb friction (N m).
const Joints kRotorInertia = (Joints() << 0.1, 0.1, 0.1, 0.02, 0.02, 0.02).finished();
const Joints kDamping = (Joints() << 2, 2, 2, 0.5, 0.5, 0.5).finished();
const Joints kFriction = (Joints() << 0.5, 0.5, 0.5, 0.1, 0.1, 0.1).finished();

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

double Sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

}  // namespace

MassProperties Combine(const MassProperties& a, const MassProperties& b) {
  MassProperties sum;
  sum.mass = a.mass + b.mass;
  if (sum.mass <= 0) return sum;
  sum.p_com = (a.mass * a.p_com + b.mass * b.p_com) / sum.mass;
  // Each body's inertia moved to the common centre of mass: I + m (|r|^2 1 - r r^T).
  for (const MassProperties* body : {&a, &b}) {
    const Eigen::Vector3d r = body->p_com - sum.p_com;
    sum.inertia += body->inertia - body->mass * Skew(r) * Skew(r);
  }
  return sum;
}

MassProperties GripperMassProperties() {
  // models/gripper/gripper_body.inc.xml: the housing and palm, and two fingers half open (their
  // centres of mass 2 cm beyond the finger joints, which sit 8.5 cm along the tool axis).
  constexpr double kHalfOpen = kMaxGap / 4;
  MassProperties gripper = Body(0.7, {0, 0, 0.05}, {0.0012, 0.0012, 0.0008});
  for (double side : {1.0, -1.0}) {
    gripper = Combine(gripper, Body(0.06, {0, side * (0.02 + kHalfOpen), 0.145}, {8e-5, 8e-5, 1e-5}));
  }
  return gripper;
}

Ur5Dynamics::Ur5Dynamics(const MassProperties& tool_F) : links_(Ur5Links()) {
  if (!(tool_F.mass >= 0) || !std::isfinite(tool_F.mass) || !tool_F.p_com.allFinite() || !tool_F.inertia.allFinite()) {
    throw std::invalid_argument("Ur5Dynamics: the tool's mass " + std::to_string(tool_F.mass) +
                                " kg and centre of mass must be finite and not negative");
  }
  // The flange is link 6's frame moved d6 along its z axis.
  MassProperties tool_in_link6 = tool_F;
  tool_in_link6.p_com.z() += kUr5Dh[5].d;
  links_[5] = Combine(links_[5], tool_in_link6);
}

Joints Ur5Dynamics::RigidBodyTorque(const Joints& q, const Joints& qd, const Joints& qdd) const {
  const LinkFrames frames = ForwardKinematicsAll(q);
  // Forward: each link's angular velocity and acceleration, and the force and moment that move it.
  // Gravity enters as the base accelerating upwards.
  std::array<Eigen::Vector3d, 6> origin, axis, lever, force, moment;
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), wd = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_origin(0, 0, kGravity), previous_origin = Eigen::Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    origin[i] = frames[i].translation();
    axis[i] = frames[i].linear().col(2);
    const Eigen::Vector3d hop = origin[i] - previous_origin;
    a_origin += wd.cross(hop) + w.cross(w.cross(hop));
    wd += qdd[i] * axis[i] + w.cross(qd[i] * axis[i]);
    w += qd[i] * axis[i];
    const Eigen::Matrix3d R = frames[i].linear() * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ());
    const MassProperties& link = links_[i];
    lever[i] = R * link.p_com;
    const Eigen::Vector3d a_com = a_origin + wd.cross(lever[i]) + w.cross(w.cross(lever[i]));
    const Eigen::Matrix3d inertia = R * link.inertia * R.transpose();
    force[i] = link.mass * a_com;
    moment[i] = inertia * wd + w.cross(inertia * w);
    previous_origin = origin[i];
  }
  // Backward: what each joint transmits to everything beyond it, about its own origin.
  Joints tau;
  Eigen::Vector3d f = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
  for (int i = 5; i >= 0; --i) {
    const Eigen::Vector3d to_next = i < 5 ? Eigen::Vector3d(origin[i + 1] - origin[i]) : Eigen::Vector3d::Zero();
    n = moment[i] + n + lever[i].cross(force[i]) + to_next.cross(f);
    f = force[i] + f;
    tau[i] = n.dot(axis[i]);
  }
  return tau;
}

Joints Ur5Dynamics::Torque(const Joints& q, const Joints& qd, const Joints& qdd) const {
  return InverseDynamics(q, qd, qdd) + Friction(qd, qdd);
}

Joints Ur5Dynamics::Gravity(const Joints& q) const { return RigidBodyTorque(q, Joints::Zero(), Joints::Zero()); }

Joints Ur5Dynamics::InverseDynamics(const Joints& q, const Joints& qd, const Joints& qdd) const {
  return RigidBodyTorque(q, qd, qdd) + kRotorInertia.cwiseProduct(qdd);
}

Joints Ur5Dynamics::Inertial(const Joints& q, const Joints& qd, const Joints& qdd) const {
  return InverseDynamics(q, qd, qdd) - Gravity(q);
}

Joints Ur5Dynamics::Friction(const Joints& qd, const Joints& qdd) {
  Joints tau = kDamping.cwiseProduct(qd);
  for (int i = 0; i < 6; ++i) tau[i] += kFriction[i] * Sign(qd[i] != 0 ? qd[i] : qdd[i]);
  return tau;
}

const Ur5Dynamics& CellArmDynamics() {
  static const Ur5Dynamics dynamics = [] {
    MassProperties payload;
    payload.mass = kPlannedPayloadKg;
    payload.p_com = Eigen::Vector3d(0, 0, kTcpOffsetZ);
    return Ur5Dynamics(Combine(GripperMassProperties(), payload));
  }();
  return dynamics;
}

}  // namespace sortcell::robot
