#include "simcell/scripted_pick.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "files/data_dir.h"
#include "files/json_fields.h"
#include "files/output_dir.h"
#include "common/wall_clock.h"
#include "simcell/sim_cell.h"
#include "simcell/sim_layout.h"
#include "cell/pick_and_place.h"
#include "robot/grasp_planner.h"
#include "robot/joint_trajectory.h"
#include "sim/ground_truth.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {
namespace {

constexpr double kPickSettleTime = 0.5;  // s, before the pick and before judging the result

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

// --bin takes "cup" or "bin_cup".
std::string FullBinName(const std::string& bin) {
  return bin.rfind(sim::BinName(""), 0) == 0 ? bin : sim::BinName(bin);
}

// The scene's object and bin named by the options.
struct PickTarget {
  int object = -1;
  sim::BinRef bin;
};

PickTarget FindTarget(const sim::Model& model, const PickOptions& options) {
  const std::vector<std::string> objects = sim::FreeBodyNames(model);
  if (std::find(objects.begin(), objects.end(), options.object) == objects.end()) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': no object named '" + options.object +
                                "' (objects: " + Join(objects) + ")");
  }
  const std::string bin_name = FullBinName(options.bin);
  std::vector<std::string> bin_names;
  PickTarget target;
  target.object = model.Id(mjOBJ_BODY, options.object);
  for (const auto& bin : sim::Bins(model)) {
    bin_names.push_back(sim::BinName(bin.name));
    if (sim::BinName(bin.name) == bin_name) target.bin = bin;
  }
  if (target.bin.body < 0) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': no bin named '" + options.bin +
                                "' (bins: " + Join(bin_names) + ")");
  }
  return target;
}

// Scripted: the object's pose and shape from the scene (ground truth), as a grasp footprint.
robot::ObjectFootprint FootprintFromScene(const sim::ObjectExtent& extent) {
  robot::ObjectFootprint footprint;
  footprint.centre_xy = extent.centre_xy;
  footprint.base_z = extent.base_z;
  footprint.top_z = extent.top_z;
  footprint.pinch_yaw = extent.pinch_yaw;
  footprint.width = extent.width;
  return footprint;
}

// The pick command's status from how the sequence ended and where the object is.
std::string PickStatus(cell::AttemptResult result, bool in_bin) {
  switch (result) {
    case cell::AttemptResult::kReleased:
      return in_bin ? "sorted" : "missed_bin";
    case cell::AttemptResult::kMissed:
      return "grasp_failed";
    case cell::AttemptResult::kDropped:
      return "dropped";
    case cell::AttemptResult::kPutBack:
    case cell::AttemptResult::kMotionFailed:
      return "unreachable";
    case cell::AttemptResult::kSimDiverged:
      return "sim_diverged";
  }
  return "unreachable";
}

nlohmann::json ResultJson(const PickOptions& options, const PickResult& result, const std::string& detail,
                          const sim::ObjectExtent& extent, const robot::GraspPlan& grasp,
                          std::optional<double> held_gap, const SimCell& cell, const cell::CellLayout& layout,
                          const std::vector<cell::PhaseSpan>& phases) {
  nlohmann::json phase_list = nlohmann::json::array();
  for (const auto& p : phases) phase_list.push_back({{"phase", p.phase}, {"start_s", p.start_s}, {"end_s", p.end_s}});
  const robot::TrackingStats& tracking = cell.tracking();
  return {{"scripted", true},
          {"note", "robot-layer check: the object's pose and shape are read from the scene definition"},
          {"scene", options.scene.string()},
          {"object", options.object},
          {"bin", FullBinName(options.bin)},
          {"status", result.status},
          {"detail", detail},
          {"in_bin", result.in_bin},
          {"held_until_release", result.held},
          {"slip_mm", result.slip_mm},
          {"slip_total_mm", result.slip_total_mm},
          {"slip_rotation_deg", result.slip_rotation_deg},
          {"cycle_time_s", result.cycle_time_s},
          {"sim_time_s", cell.Now()},
          {"wall_time_s", result.wall_time_s},
          {"real_time_factor", result.real_time_factor},
          {"grasp",
           {{"pinch_yaw", extent.pinch_yaw},
            {"object_width_m", extent.width},
            {"open_gap_m", grasp.open_gap},
            {"grasp_height_m", grasp.grasp_height},
            {"held_gap_m", files::OrNull(held_gap)}}},
          {"tracking",
           {{"max_error_rad", tracking.max_error},
            {"rms_error_rad", tracking.rms_error()},
            {"saturated_samples", tracking.saturated_samples},
            {"control_rate_hz", std::lround(1.0 / layout.control_period)}}},
          {"phases", phase_list},
          {"video", options.video.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.video.string())},
          {"video_frames", result.video_frames},
          {"video_render_wall_s", result.video_render_wall_s}};
}

// How far the held object moved in the hand between the sequence's milestones (ground truth): the pick's
// hooks write the slip into `result` and the finger gap the grasp closed to into `held_gap`.
struct SlipWatch {
  SlipWatch(const sim::Data& data, int tcp, int object, SimCell& cell, cell::MotionSequencer& motions,
            PickResult& result)
      : data(data), tcp(tcp), object(object), cell(cell), motions(motions), result(result) {}

  const sim::Data& data;
  int tcp, object;
  SimCell& cell;
  cell::MotionSequencer& motions;
  PickResult& result;
  Eigen::Isometry3d X_TO_grasped = Eigen::Isometry3d::Identity(), X_TO_lifted = Eigen::Isometry3d::Identity();
  std::optional<double> held_gap;

  Eigen::Isometry3d ObjectInTcp() const { return sim::SitePose(data, tcp).inverse() * sim::BodyPose(data, object); }

  cell::PickHooks Hooks() {
    cell::PickHooks hooks;
    hooks.grasped = [this] {
      X_TO_grasped = ObjectInTcp();
      held_gap = cell.ReadGripper().gap();
    };
    hooks.lifted = [this] { X_TO_lifted = ObjectInTcp(); };
    hooks.carried = [this] {
      result.slip_mm = 1000 * (ObjectInTcp().translation() - X_TO_lifted.translation()).norm();
      result.slip_rotation_deg = robot::RotationError(ObjectInTcp(), X_TO_lifted) * 180 / M_PI;
    };
    hooks.lowered = [this] {
      result.held = motions.Hold() == robot::HoldState::kHolding;
      result.slip_total_mm = 1000 * (ObjectInTcp().translation() - X_TO_grasped.translation()).norm();
    };
    return hooks;
  }
};

// The cell's pick-and-place sequence into the middle of `bin`, then home: how it ended, and why (`detail`).
cell::AttemptResult PickIntoBin(cell::MotionSequencer& motions, const robot::GraspPlan& grasp,
                                const cell::CellLayout& layout, const std::string& bin, const cell::PickHooks& hooks,
                                std::string& detail) {
  cell::PickRequest request;
  request.grasp = grasp;
  request.p_W_release = cell::BinNamed(layout, bin).p_W_floor;    // The bin's middle.
  request.place_yaw_step = robot::GraspOptions().place_yaw_step;  // Any yaw: the bin's middle.
  request.q_home = layout.q_observe;
  request.speeds = layout.speeds;
  const cell::PickReport report = cell::PickAndPlace(motions, request, hooks);
  detail = report.detail;
  if (report.exit && !cell::GoHome(motions, report.exit, layout.q_observe, layout.speeds)) {
    detail = motions.failure();
    return motions.faulted() ? cell::AttemptResult::kSimDiverged : cell::AttemptResult::kMotionFailed;
  }
  return report.result;
}

}  // namespace

PickResult RunPick(const PickOptions& options, const std::vector<std::string>& command_line) {
  const auto wall_start = WallClock::now();
  files::PrepareOutputDir(options.out);
  const files::CellFile cell_file = files::ReadCellFileOrDefault(options.cell);
  const sim::Model model = LoadCellScene(options.scene, cell_file);
  const PickTarget target = FindTarget(model, options);
  const cell::CellLayout layout = ReadCellLayout(model, cell_file);
  const int tcp = model.Id(mjOBJ_SITE, "tcp");

  sim::Data data(model);
  sim::ResetToObserve(model, data);
  std::unique_ptr<sim::VideoRecorder> video;
  if (!options.video.empty()) {
    if (options.video.has_parent_path()) std::filesystem::create_directories(options.video.parent_path());
    video = std::make_unique<sim::VideoRecorder>(model, options.video, options.video_options);
  }
  SimCell cell(model, data, nullptr, nullptr, nullptr, video.get(), layout.control_period);
  cell.Reset(layout.q_observe, layout.observe_half_gap);
  cell::MotionSequencer motions(cell);
  motions.Wait("settle", kPickSettleTime);

  const sim::ObjectExtent extent = sim::ObjectExtentOf(model, data, target.object);
  const robot::GraspPlan grasp = robot::PlanTopDownGrasp(FootprintFromScene(extent), cell.CommandedJoints());

  PickResult result;
  const double t0 = cell.Now();
  SlipWatch slip(data, tcp, target.object, cell, motions, result);
  std::string detail;
  std::optional<cell::AttemptResult> outcome;
  if (grasp.status == robot::GraspStatus::kOk) {
    outcome = PickIntoBin(motions, grasp, layout, target.bin.name, slip.Hooks(), detail);
  }
  result.cycle_time_s = cell.Now() - t0;
  motions.Wait("settle_result", kPickSettleTime);
  result.in_bin = sim::InBin(data, target.object, target.bin);
  result.status = outcome ? PickStatus(*outcome, result.in_bin) : robot::ToString(grasp.status);
  if (video) {
    video->Close();
    result.video_frames = video->frames();
    result.video_render_wall_s = video->render_wall_s();
  }
  result.wall_time_s = SecondsSince(wall_start);
  result.real_time_factor = cell.Now() / result.wall_time_s;
  files::WriteJson(options.out / "result.json",
                   ResultJson(options, result, detail, extent, grasp, slip.held_gap, cell, layout, motions.phases()));
  files::WriteJson(
      options.out / "run.json",
      files::RunRecord(command_line, 0,
                       {{"command", "pick"}, {"scene", options.scene.string()}, {"wall_time_s", result.wall_time_s}}));
  return result;
}

}  // namespace sortcell::simcell
