#include "app/cli/kinematics_commands.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "cell/cell_layout.h"
#include "robot/ik_selection.h"
#include "robot/ur5_ik.h"

namespace sortcell::app {
namespace {

const char* const kFrameHelp =
    "Frames: the pose is the flange's (D-H frame 6) in the Base frame (D-H frame 0 = the world frame of "
    "the cell, z up); with --tcp, the gripper's tool centre point (0.185 m along the flange's z). "
    "R = Rz(yaw) Ry(pitch) Rx(roll). Metres and radians.";

robot::Joints JointsFrom(const std::vector<double>& values, const std::string& option) {
  if (values.size() != 6) {
    throw std::invalid_argument(option + ": expected 6 joint values, found " + std::to_string(values.size()));
  }
  robot::Joints q;
  for (int i = 0; i < 6; ++i) {
    if (!std::isfinite(values[i]))
      throw std::invalid_argument(option + ": value " + std::to_string(i + 1) + " is not finite");
    q[i] = values[i];
  }
  return q;
}

std::string FrameName(bool tcp) {
  return tcp ? "tcp in base (D-H frame 0)" : "flange (D-H frame 6) in base (D-H frame 0)";
}

nlohmann::json ToJson(const robot::Joints& q) { return std::vector<double>(q.data(), q.data() + 6); }

}  // namespace

nlohmann::json IkJson(const std::vector<double>& pose, const std::vector<double>& q_near_values, bool tcp) {
  if (pose.size() != 6) throw std::invalid_argument("--pose: expected x y z roll pitch yaw (6 values)");
  for (double v : pose) {
    if (!std::isfinite(v)) throw std::invalid_argument("--pose: values must be finite numbers");
  }
  const robot::Joints q_near =
      q_near_values.empty() ? cell::CellLayout().q_observe : JointsFrom(q_near_values, "--q-near");
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << pose[0], pose[1], pose[2];
  X.linear() = robot::RotationFromRpy(pose[3], pose[4], pose[5]);
  const robot::IkResult ik = tcp ? robot::SolveTcpIk(X, q_near[5]) : robot::SolveIk(X, q_near[5]);

  nlohmann::json solutions = nlohmann::json::array();
  for (int k = 0; k < ik.count; ++k) {
    const robot::IkSolution& s = ik.solutions[k];
    solutions.push_back({{"q", ToJson(s.q)},
                         {"position_error", s.position_error},
                         {"rotation_error", s.rotation_error},
                         {"wrist_singular", s.wrist_singular}});
  }
  const auto nearest = robot::SelectNearest(ik, q_near);
  return {{"frame", FrameName(tcp)},
          {"solutions", solutions},
          {"nearest", nearest ? nlohmann::json(nearest->index) : nlohmann::json(nullptr)},
          {"nearest_q", nearest ? ToJson(nearest->q) : nlohmann::json(nullptr)},
          {"q_near", ToJson(q_near)},
          {"status", ik.status == robot::IkStatus::kOk ? "ok" : "unreachable"}};
}

nlohmann::json FkJson(const std::vector<double>& values, bool tcp) {
  const robot::Joints q = JointsFrom(values, "--q");
  const Eigen::Isometry3d X = tcp ? robot::TcpPose(q) : robot::FlangePose(q);
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) rotation.push_back({X.linear()(r, 0), X.linear()(r, 1), X.linear()(r, 2)});
  const Eigen::Vector3d rpy = robot::RpyFromRotation(X.linear());
  return {{"frame", FrameName(tcp)},
          {"position", {X.translation().x(), X.translation().y(), X.translation().z()}},
          {"rotation", rotation},
          {"rpy", {rpy[0], rpy[1], rpy[2]}}};
}

void AddKinematicsCommands(CLI::App& app, std::function<int()>& run) {
  struct Options {
    std::vector<double> pose, q_near, q;
    bool tcp = false;
  };
  auto options = std::make_shared<Options>();

  CLI::App* ik = app.add_subcommand(
      "ik", std::string("Analytic UR5 inverse kinematics: every solution (up to 8), each checked by forward "
                        "kinematics, and the one nearest to --q-near inside the joint limits with the links "
                        "above the table. JSON on stdout. ") +
                kFrameHelp);
  ik->add_option("--pose", options->pose, "x y z roll pitch yaw")->expected(6)->required()->allow_extra_args(false);
  ik->add_option("--q-near", options->q_near, "Current joints q1..q6 (default: the home pose)")->expected(6);
  ik->add_flag("--tcp", options->tcp, "The pose is the gripper TCP's, not the flange's");
  ik->callback([&run, options] {
    run = [options] {
      const nlohmann::json result = IkJson(options->pose, options->q_near, options->tcp);
      std::cout << result.dump(2) << "\n";
      return result["status"] == "ok" ? 0 : 1;  // unreachable: a result, not an error
    };
  });

  CLI::App* fk = app.add_subcommand(
      "fk", std::string("UR5 forward kinematics from the D-H table: the pose for joints q1..q6. JSON on stdout. ") +
                kFrameHelp);
  fk->add_option("--q", options->q, "q1 q2 q3 q4 q5 q6 (rad)")->expected(6)->required();
  fk->add_flag("--tcp", options->tcp, "The gripper TCP's pose instead of the flange's");
  fk->callback([&run, options] {
    run = [options] {
      std::cout << FkJson(options->q, options->tcp).dump(2) << "\n";
      return 0;
    };
  });
}

}  // namespace sortcell::app
