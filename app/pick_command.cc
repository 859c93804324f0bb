#include "app/pick_command.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/arm_executor.h"
#include "app/motion_runner.h"
#include "app/output_dir.h"
#include "robot/grasp_planner.h"
#include "robot/gripper_control.h"
#include "robot/joint_trajectory.h"
#include "sim/ground_truth.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::app {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kApproachSpeed = 0.10;    // m/s, the last straight descent onto the object
constexpr double kSettleTime = 0.5;         // s, before the pick and before judging the result

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace

// TCP at (0.281, 0.109, 0.446), tool down, upper arm leaning back: above and behind the workspace's
// near edge, where no ray from the Kinect to the table or an object passes (those rays are below
// the table there), and high enough that every transit starts above the tallest objects. The IK
// branch nearest to it (shoulder facing the workspace, elbow up) is the natural one for picking.
robot::Joints HomeJoints() {
  return (robot::Joints() << M_PI, -1.9, 1.3, -M_PI_2 + 0.6, -M_PI_2, 0).finished();
}

PickResult RunPick(const PickOptions& options, const std::vector<std::string>& command_line) {
  const auto wall_start = Clock::now();
  PrepareOutputDir(options.out);
  const sim::Model model = sim::Model::FromFile(options.scene.string());
  const std::vector<std::string> objects = sim::FreeBodyNames(model);
  if (std::find(objects.begin(), objects.end(), options.object) == objects.end()) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': no object named '" + options.object +
                                "' (objects: " + Join(objects) + ")");
  }
  const std::string bin_name = options.bin.rfind("bin_", 0) == 0 ? options.bin : "bin_" + options.bin;
  const std::vector<std::string> bins = sim::BinNames(model);
  if (std::find(bins.begin(), bins.end(), bin_name) == bins.end()) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': no bin named '" + options.bin +
                                "' (bins: " + Join(bins) + ")");
  }
  const int object = model.Id(mjOBJ_BODY, options.object);
  const int bin = model.Id(mjOBJ_BODY, bin_name);
  const int tcp = model.Id(mjOBJ_SITE, "tcp");
  const int bin_site = model.Id(mjOBJ_SITE, bin_name);

  sim::Data data(model);
  sim::ResetToObserve(model, data);
  std::unique_ptr<sim::VideoRecorder> video;
  if (!options.video.empty()) {
    if (options.video.has_parent_path()) std::filesystem::create_directories(options.video.parent_path());
    video = std::make_unique<sim::VideoRecorder>(model, options.video);
  }
  MotionRunner run(model, data, video.get());
  ArmExecutor& exec = run.exec();
  exec.Reset(HomeJoints(), robot::kMaxGap / 2);
  run.Wait("settle", kSettleTime);

  // Scripted: the object's pose and shape from the scene (ground truth), as a grasp footprint.
  const sim::ObjectExtent extent = sim::ObjectExtentOf(model, data, object);
  robot::ObjectFootprint footprint;
  footprint.centre_xy = extent.centre_xy;
  footprint.base_z = extent.base_z;
  footprint.top_z = extent.top_z;
  footprint.pinch_yaw = extent.pinch_yaw;
  footprint.width = extent.width;
  const robot::GraspPlan grasp = robot::PlanTopDownGrasp(footprint, exec.ReferenceJoints());

  PickResult result;
  const double t0 = exec.time();
  robot::HoldState hold = robot::HoldState::kEmpty;
  Eigen::Isometry3d X_TO_grasped = Eigen::Isometry3d::Identity();
  const auto object_in_tcp = [&] { return sim::SitePose(data, tcp).inverse() * sim::BodyPose(data, object); };

  const auto pick_and_place = [&]() -> std::string {
    if (grasp.status != robot::GraspStatus::kOk) return robot::ToString(grasp.status);
    if (!run.Gripper("open", grasp.open_gap, hold) || !run.MoveJ("approach", grasp.q_lift) ||
        !run.MoveL("descend", grasp.X_WT_pregrasp, robot::kMovelSpeed) ||
        !run.MoveL("reach", grasp.X_WT_grasp, kApproachSpeed) || !run.Grasp("grasp", hold)) {
      return run.FailureStatus();
    }
    if (hold != robot::HoldState::kHolding) return "grasp_failed";
    X_TO_grasped = object_in_tcp();
    if (!run.MoveL("lift", grasp.X_WT_lift, robot::kMovelSpeed)) return run.FailureStatus();
    const Eigen::Isometry3d X_TO_lifted = object_in_tcp();
    const robot::PlacePlan place =
        robot::PlanPlacement(sim::SitePose(data, bin_site).translation(), grasp.grasp_height, exec.ReferenceJoints());
    if (!place.ok) return "unreachable";
    if (!run.MoveJ("carry", place.q_above)) return run.FailureStatus();
    result.slip_mm = 1000 * (object_in_tcp().translation() - X_TO_lifted.translation()).norm();
    result.slip_rotation_deg = robot::RotationError(object_in_tcp(), X_TO_lifted) * 180 / M_PI;
    if (!run.MoveL("lower", place.X_WT_release, robot::kMovelSpeed)) return run.FailureStatus();
    result.held = robot::DetectHold(exec.Gripper()) == robot::HoldState::kHolding;
    result.slip_total_mm = 1000 * (object_in_tcp().translation() - X_TO_grasped.translation()).norm();
    if (!run.Gripper("release", grasp.open_gap, hold) || !run.MoveL("retreat", place.X_WT_above, robot::kMovelSpeed) ||
        !run.MoveJ("home", HomeJoints())) {
      return run.FailureStatus();
    }
    return "";
  };
  std::string status = pick_and_place();
  result.cycle_time_s = exec.time() - t0;
  run.Wait("settle_result", kSettleTime);
  result.in_bin = sim::InBin(data, object, bin);
  if (status.empty()) status = result.in_bin ? "sorted" : "missed_bin";
  result.status = status;
  if (video) {
    video->Close();
    result.video_frames = video->frames();
    result.video_render_wall_s = video->render_wall_s();
  }
  result.wall_time_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  result.real_time_factor = exec.time() / result.wall_time_s;

  const robot::TrackingStats& tracking = exec.tracking();
  const nlohmann::json json = {
      {"scripted", true},
      {"note", "robot-layer check: the object's pose and shape are read from the scene definition"},
      {"scene", options.scene.string()},
      {"object", options.object},
      {"bin", bin_name},
      {"status", status},
      {"detail", run.failure()},
      {"in_bin", result.in_bin},
      {"held_until_release", result.held},
      {"slip_mm", result.slip_mm},
      {"slip_total_mm", result.slip_total_mm},
      {"slip_rotation_deg", result.slip_rotation_deg},
      {"cycle_time_s", result.cycle_time_s},
      {"sim_time_s", exec.time()},
      {"wall_time_s", result.wall_time_s},
      {"real_time_factor", result.real_time_factor},
      {"grasp",
       {{"pinch_yaw", extent.pinch_yaw},
        {"object_width_m", extent.width},
        {"open_gap_m", grasp.open_gap},
        {"grasp_height_m", grasp.grasp_height},
        {"held_gap_m", exec.Gripper().gap()}}},
      {"tracking",
       {{"max_error_rad", tracking.max_error},
        {"rms_error_rad", tracking.rms_error()},
        {"saturated_samples", tracking.saturated_samples},
        {"control_rate_hz", 500}}},
      {"phases", run.phases()},
      {"video", options.video.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.video.string())},
      {"video_frames", result.video_frames},
      {"video_render_wall_s", result.video_render_wall_s}};
  WriteJson(options.out / "result.json", json);
  WriteJson(options.out / "run.json",
            RunRecord(command_line, 0, {{"command", "pick"}, {"scene", options.scene.string()}, {"wall_time_s", result.wall_time_s}}));
  return result;
}

void AddPickCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto options = std::make_shared<PickOptions>();
  CLI::App* cmd = app.add_subcommand(
      "pick",
      "Scripted robot-layer check: pick one object whose pose is read from the scene definition (not "
      "perceived), with a top-down friction grasp, and place it in a bin. Writes result.json (in_bin, "
      "slip_mm, cycle_time_s, wall_time_s, phases, tracking error) and run.json.");
  cmd->add_option("--scene", options->scene, "MJCF scene file, e.g. scenes/cell.xml")->required();
  cmd->add_option("--object", options->object, "Object (free body) to pick, e.g. bottle1")->required();
  cmd->add_option("--bin", options->bin, "Bin to place it in: bottle, cup, ball or others (or bin_<name>)")
      ->required();
  cmd->add_option("--video", options->video, "Also write an H.264 MP4 from the review camera (30 fps)");
  options->out = "out/pick";
  cmd->add_option("--out", options->out, "Output folder (created if missing)")->capture_default_str();
  cmd->callback([&run, options, command_line] {
    run = [options, command_line] {
      const PickResult r = RunPick(*options, command_line);
      std::cout << "Pick " << options->object << " -> " << options->bin << " (scripted pose): " << r.status
                << (r.in_bin ? ", in the bin" : ", NOT in the bin") << ", slip " << r.slip_mm << " mm, cycle "
                << r.cycle_time_s << " s simulated, " << r.wall_time_s << " s wall (real-time factor "
                << r.real_time_factor << ")" << (r.video_frames ? ", video " + std::to_string(r.video_frames) + " frames" : "")
                << ". Result: " << (options->out / "result.json").string() << "\n";
      return r.status == "sorted" ? 0 : 1;
    };
  });
}

}  // namespace sortcell::app
