#include "app/episode.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>

#include "app/episode_scoring.h"
#include "app/motion_runner.h"
#include "app/object_set.h"
#include "app/output_dir.h"
#include "app/pick_command.h"
#include "app/seeding.h"
#include "app/wall_clock.h"
#include "perception/descriptor.h"
#include "perception/recognition_model.h"
#include "perception/segment_overlay.h"
#include "perception/segmentation.h"
#include "robot/footprint_estimation.h"
#include "robot/grasp_planner.h"
#include "robot/gripper_geometry.h"
#include "robot/pick_selection.h"
#include "sim/camera_model.h"
#include "sim/ground_truth.h"
#include "sim/kinect_camera.h"
#include "sim/object_placement.h"
#include "sim/point_cloud.h"
#include "sim/video_recorder.h"

namespace sortcell::app {
namespace {

constexpr double kSettleTime = 1.0;      // s, after placing the objects and before scoring
constexpr double kApproachSpeed = 0.10;  // m/s, the last straight descent onto the object
constexpr int kDefaultMaxObjects = 6;
// Random placements: the reachable middle of the workspace, 3 cm of free table between footprints so
// the open fingers fit between neighbours and objects segment apart.
const Eigen::Vector2d kAreaMin(0.32, -0.22), kAreaMax(0.68, 0.22);
constexpr double kGap = 0.03;
// Finger clearance per side for a perceived width (Kinect noise ~2 mm at 1 m), reduced down to the
// scripted pick's 4.5 mm when the object is that close to the stroke.
constexpr double kPerceivedClearance = 0.008, kMinClearance = 0.0045;

std::string Fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// What the loop knows of one cluster of the current capture.
struct Detection {
  perception::Segment segment;
  robot::ObjectFootprint footprint;
  std::optional<std::string> category;  // Empty when it could not be described.
  double confidence = 0;
};

// The robot's fixed knowledge of its cell, as a calibration gives it: the Kinect's nominal pose, the
// bins' floor centres and the empty table seen by the Kinect.
struct CellCalibration {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  std::map<std::string, Eigen::Vector3d> p_W_bin;
  perception::Cloud::Ptr background;
};

std::vector<ObjectSpec> ChooseObjects(const ObjectSet& set, const EpisodeOptions& options, std::mt19937_64& rng) {
  const int n = static_cast<int>(set.objects.size());
  const int count = options.objects > 0 ? options.objects : std::min(n, kDefaultMaxObjects);
  if (count < 1 || count > n) {
    throw std::invalid_argument("--objects: expected 1.." + std::to_string(n) + " (the objects of set '" +
                                set.source.string() + "'), got " + std::to_string(options.objects));
  }
  if (static_cast<int>(options.placements.size()) > count) {
    throw std::invalid_argument("--place: " + std::to_string(options.placements.size()) +
                                " placements for " + std::to_string(count) + " objects");
  }
  std::vector<ObjectSpec> chosen;
  std::set<std::string> names;
  for (const auto& p : options.placements) {
    if (!names.insert(p.name).second) throw std::invalid_argument("--place: object '" + p.name + "' placed twice");
    chosen.push_back(set.Find(p.name));
  }
  std::vector<ObjectSpec> others;
  for (const auto& spec : set.objects) {
    if (!names.count(spec.name)) others.push_back(spec);
  }
  std::shuffle(others.begin(), others.end(), rng);
  for (int i = 0; static_cast<int>(chosen.size()) < count; ++i) chosen.push_back(others[i]);
  return chosen;
}

class EpisodeRun {
 public:
  EpisodeRun(const EpisodeOptions& options, const ObjectSet& set, const perception::RecognitionModel& recognizer)
      : options_(options), set_(set), recognizer_(recognizer), rng_(EpisodeRng(options.seed, 0)),
        model_(sim::Model::FromFile(options.scene.string())) {}

  nlohmann::json Run(const std::vector<std::string>& command_line);

 private:
  void SetUpScene();
  std::vector<Detection> Observe();
  // One pick-and-sort attempt of detection `d` with grasp `plan`. Returns the loop's view of how it
  // went: "released", "missed", "dropped", "motion_failed", "sim_diverged".
  std::string PickAndSort(const Detection& d, const robot::GraspPlan& plan, AttemptRecord& record);
  void ShowStatus(const std::string& current);
  void ShowObservation(const perception::Cloud& cloud, const std::vector<Detection>& detections);

  const EpisodeOptions& options_;
  const ObjectSet& set_;
  const perception::RecognitionModel& recognizer_;
  std::mt19937_64 rng_;
  sim::Model model_;
  std::unique_ptr<sim::Data> data_;
  std::unique_ptr<sim::KinectCamera> kinect_;
  std::unique_ptr<sim::VideoRecorder> video_;
  std::unique_ptr<MotionRunner> run_;
  std::unique_ptr<EpisodeScorer> scorer_;
  CellCalibration calibration_;
  std::vector<PlacedObject> placed_;
  perception::SegmentationParams segmentation_;
  sim::KinectNoiseParams noise_;
  // Running figures.
  std::map<std::string, int> released_into_;  // Objects the loop put into each category's bin.
  int frames_ = 0, released_ = 0, missed_ = 0, dropped_ = 0, skipped_ = 0;
  double perception_wall_s_ = 0, render_wall_s_ = 0;
  nlohmann::json attempts_log_ = nlohmann::json::array();
};

void EpisodeRun::SetUpScene() {
  // Calibration first, from the nominal cell: the robot keeps it when a sweep displaces the camera.
  {
    sim::Data nominal(model_);
    mj_forward(model_.get(), nominal.get());  // Camera poses come from mj_camlight, inside mj_forward.
    calibration_.X_WC = sim::CameraPoseInWorld(model_, nominal, model_.Id(mjOBJ_CAMERA, "kinect"));
    for (const auto& bin : sim::BinNames(model_)) {
      calibration_.p_W_bin[bin.substr(4)] = sim::SitePose(nominal, model_.Id(mjOBJ_SITE, bin)).translation();
    }
  }
  for (const auto& c : recognizer_.classes) {
    if (!calibration_.p_W_bin.count(c)) {
      throw std::invalid_argument("model '" + options_.model.string() + "': class '" + c + "' has no bin 'bin_" + c +
                                  "' in scene '" + options_.scene.string() + "'");
    }
  }
  sim::ApplyVariation(model_, options_.variation, rng_);
  data_ = std::make_unique<sim::Data>(model_);
  kinect_ = std::make_unique<sim::KinectCamera>(model_, "kinect");
  sim::Lighting lighting;
  lighting.intensity = options_.light_intensity;
  kinect_->SetLighting(lighting);
  noise_.noise_scale = options_.noise_scale;
  // The pick area the camera watches: the table in front of the robot up to its far edge (objects out
  // of reach there are seen and reported unreachable), between the bins.
  segmentation_.workspace_min_W = Eigen::Vector3d(0.28, -0.34, -0.05);
  segmentation_.workspace_max_W = Eigen::Vector3d(0.88, 0.34, 0.40);

  // Every object stowed out of view, the arm at its observe pose: the empty cell for background subtraction.
  const std::vector<std::string> bodies = sim::FreeBodyNames(model_);
  for (size_t i = 0; i < bodies.size(); ++i) sim::StowObject(model_, *data_, model_.Id(mjOBJ_BODY, bodies[i]), static_cast<int>(i));
  if (!options_.video.empty()) {
    if (options_.video.has_parent_path()) std::filesystem::create_directories(options_.video.parent_path());
    video_ = std::make_unique<sim::VideoRecorder>(model_, options_.video);
  }
  run_ = std::make_unique<MotionRunner>(model_, *data_, video_.get());
  run_->exec().Reset(HomeJoints(), robot::kMaxGap / 2);
  calibration_.background = sim::ToOrganizedCloud(kinect_->Capture(*data_, &noise_, &rng_));

  // The objects: chosen, then placed where asked or at random non-overlapping poses.
  const std::vector<ObjectSpec> chosen = ChooseObjects(set_, options_, rng_);
  std::vector<sim::TablePose> poses;
  for (const auto& p : options_.placements) poses.push_back({p.x, p.y, p.yaw});
  std::vector<double> radii;
  for (const auto& spec : chosen) radii.push_back(sim::FootprintRadius(model_, *data_, model_.Id(mjOBJ_BODY, spec.name)));
  const size_t fixed = poses.size();
  std::vector<double> random_radii(radii.begin() + fixed, radii.end());
  bool placed = false;
  for (int tries = 0; tries < 50 && !placed; ++tries) {
    const auto drawn = sim::SampleTablePoses(random_radii, kAreaMin, kAreaMax, kGap, rng_);
    if (!drawn) break;
    placed = true;
    for (size_t i = 0; i < fixed && placed; ++i) {
      for (size_t j = 0; j < drawn->size(); ++j) {
        const double d = std::hypot(poses[i].x - (*drawn)[j].x, poses[i].y - (*drawn)[j].y);
        if (d < radii[i] + random_radii[j] + kGap) placed = false;
      }
    }
    if (placed) poses.insert(poses.end(), drawn->begin(), drawn->end());
  }
  if (!placed) {
    throw std::invalid_argument("--objects: " + std::to_string(chosen.size()) +
                                " objects do not fit the table area with the given placements");
  }
  const std::vector<std::string>& label_names = kinect_->object_names();
  for (size_t i = 0; i < chosen.size(); ++i) {
    const int body = model_.Id(mjOBJ_BODY, chosen[i].name);
    sim::PlaceObject(model_, *data_, body, poses[i].x, poses[i].y, poses[i].yaw);
    const int label = static_cast<int>(std::find(label_names.begin(), label_names.end(), chosen[i].name) -
                                       label_names.begin()) + 1;
    placed_.push_back({chosen[i].name, chosen[i].category, body, label});
  }
  mj_forward(model_.get(), data_->get());
  scorer_ = std::make_unique<EpisodeScorer>(placed_, static_cast<int>(label_names.size()));
}

std::vector<Detection> EpisodeRun::Observe() {
  run_->exec().SetPhase("observe");
  auto start = WallClock::now();
  const sim::KinectFrame frame = kinect_->Capture(*data_, &noise_, &rng_);
  const perception::Cloud::Ptr cloud = sim::ToOrganizedCloud(frame);
  render_wall_s_ += SecondsSince(start);
  ++frames_;

  // From here on the loop sees the cloud and its calibration only (frame.labels goes to the scorer).
  start = WallClock::now();
  std::vector<Detection> detections;
  perception::SegmentationResult segmented;
  try {
    segmented = perception::SegmentObjects(*cloud, calibration_.X_WC, calibration_.background.get(), segmentation_);
  } catch (const std::invalid_argument&) {
    // No usable table in view (e.g. a badly displaced camera): nothing to pick from this capture.
    perception_wall_s_ += SecondsSince(start);
    scorer_->Observe(frame.labels, {});
    return detections;
  }
  // The table's height under each object, from the fitted plane (n.p + d = 0 in C).
  const Eigen::Vector3d n_W = calibration_.X_WC.linear() * segmented.plane_C.head<3>();
  const double d_W = segmented.plane_C[3] - n_W.dot(calibration_.X_WC.translation());
  for (auto& segment : segmented.segments) {
    Detection d;
    std::vector<Eigen::Vector3d> p_W;
    p_W.reserve(segment.cloud_C->size());
    for (const auto& p : segment.cloud_C->points) p_W.push_back(calibration_.X_WC * Eigen::Vector3d(p.x, p.y, p.z));
    if (p_W.size() < 10) continue;
    const Eigen::Vector3d c = segment.centroid;
    const double table_z = std::abs(n_W.z()) > 1e-6 ? -(n_W.x() * c.x() + n_W.y() * c.y() + d_W) / n_W.z() : 0.0;
    d.footprint = robot::EstimateFootprint(p_W, calibration_.X_WC.translation(), table_z).footprint;
    try {
      const auto result = recognizer_.Classify(perception::ComputeDescriptorParts(*segment.cloud_C, recognizer_.params));
      d.category = result.name;
      d.confidence = result.confidence;
    } catch (const std::invalid_argument&) {
      // Too few points to describe (a fragment): seen, but not sortable.
    }
    d.segment = std::move(segment);
    detections.push_back(std::move(d));
  }
  perception_wall_s_ += SecondsSince(start);

  std::vector<DetectionRecord> records;
  for (const auto& d : detections) records.push_back({&d.segment.indices, d.category, d.confidence});
  scorer_->Observe(frame.labels, records);
  if (video_) ShowObservation(*cloud, detections);
  return detections;
}

void EpisodeRun::ShowObservation(const perception::Cloud& cloud, const std::vector<Detection>& detections) {
  std::vector<perception::Segment> segments;
  for (const auto& d : detections) segments.push_back(d.segment);
  cv::Mat overlay = perception::SegmentOverlay(cloud, segments);
  for (size_t i = 0; i < detections.size(); ++i) {
    // Outline and name each cluster where it is in the image.
    cv::Mat mask = cv::Mat::zeros(overlay.size(), CV_8UC1);
    for (int p : detections[i].segment.indices) mask.at<uint8_t>(p / mask.cols, p % mask.cols) = 255;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(overlay, contours, -1, cv::Scalar(255, 255, 255), 2);
    const cv::Rect box = cv::boundingRect(mask);
    const std::string text = std::to_string(i) + " " +
                             (detections[i].category ? *detections[i].category + " " + Fixed(detections[i].confidence, 2) : "?");
    const cv::Point at(box.x, std::max(14, box.y - 6));
    cv::putText(overlay, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
    cv::putText(overlay, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2, cv::LINE_AA);
  }
  video_->SetInset(overlay);
}

void EpisodeRun::ShowStatus(const std::string& current) {
  if (!video_) return;
  video_->SetOverlay({"seed " + std::to_string(options_.seed) + "   objects " + std::to_string(placed_.size()) +
                          "   frames " + std::to_string(frames_),
                      current,
                      "released into bins " + std::to_string(released_) + "   missed grasps " + std::to_string(missed_) +
                          "   dropped " + std::to_string(dropped_) + "   skipped " + std::to_string(skipped_)});
}

std::string EpisodeRun::PickAndSort(const Detection& d, const robot::GraspPlan& plan, AttemptRecord& record) {
  MotionRunner& run = *run_;
  ArmExecutor& exec = run.exec();
  robot::HoldState hold = robot::HoldState::kEmpty;
  const auto fail = [&]() -> std::string {
    if (run.diverged()) return "sim_diverged";
    // A motion that could not be planned: let go of whatever is held and go back to observe.
    run.Gripper("open", robot::kMaxGap, hold);
    return run.MoveJ("home", HomeJoints()) ? "motion_failed" : "sim_diverged";
  };
  if (!run.Gripper("open", plan.open_gap, hold) || !run.MoveJ("approach", plan.q_lift) ||
      !run.MoveL("descend", plan.X_WT_pregrasp, robot::kMovelSpeed) ||
      !run.MoveL("reach", plan.X_WT_grasp, kApproachSpeed) || !run.Grasp("grasp", hold)) {
    return fail();
  }
  if (hold != robot::HoldState::kHolding) {
    if (!run.Gripper("open", plan.open_gap, hold) || !run.MoveL("retreat", plan.X_WT_lift, robot::kMovelSpeed) ||
        !run.MoveJ("home", HomeJoints())) {
      return fail();
    }
    return "missed";
  }
  record.grasped = true;
  if (!run.MoveL("lift", plan.X_WT_lift, robot::kMovelSpeed)) return fail();
  if (robot::DetectHold(exec.Gripper()) == robot::HoldState::kEmpty) {
    run.Gripper("open", robot::kMaxGap, hold);
    return run.MoveJ("home", HomeJoints()) ? "dropped" : "sim_diverged";
  }
  record.lifted = true;
  // Each bin is filled slot by slot (its quadrants, then the middle), the held object square to the
  // bin, so a bin takes four objects without dropping one onto another.
  static const Eigen::Vector3d kSlots[] = {{-0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}, {0.05, -0.05, 0}, {0, 0, 0}};
  int& filled = released_into_[*d.category];
  robot::GraspOptions place_options;
  place_options.place_yaw_step = M_PI / 2;
  const robot::PlacePlan place = robot::PlanPlacement(calibration_.p_W_bin.at(*d.category) + kSlots[filled % 5],
                                                      plan.grasp_height, exec.ReferenceJoints(), place_options);
  if (!place.ok) {
    // The bin cannot be reached from here (not in the default cell): put the object back down.
    if (!run.MoveL("put_back", plan.X_WT_grasp, robot::kMovelSpeed)) return fail();
    run.Gripper("open", plan.open_gap, hold);
    if (!run.MoveL("retreat", plan.X_WT_lift, robot::kMovelSpeed) || !run.MoveJ("home", HomeJoints())) return fail();
    return "motion_failed";
  }
  if (!run.MoveJ("carry", place.q_above)) return fail();
  // Judged above the bin: lowering into it may touch what is already there and move the fingers.
  const bool held = robot::DetectHold(exec.Gripper()) != robot::HoldState::kEmpty;
  if (!run.MoveL("lower", place.X_WT_release, robot::kMovelSpeed)) return fail();
  if (!run.Gripper("release", plan.open_gap, hold) || !run.MoveL("retreat", place.X_WT_above, robot::kMovelSpeed) ||
      !run.MoveJ("home", HomeJoints())) {
    return fail();
  }
  ++filled;
  return held ? "released" : "dropped";
}

nlohmann::json EpisodeRun::Run(const std::vector<std::string>& command_line) {
  const auto wall_start = WallClock::now();
  SetUpScene();
  MotionRunner& run = *run_;
  ArmExecutor& exec = run.exec();
  ShowStatus("settling");
  run.Wait("settle", kSettleTime);

  const int objects = static_cast<int>(placed_.size());
  const double time_limit = options_.time_limit_s > 0 ? options_.time_limit_s : 60.0 + 45.0 * objects;
  const int max_attempts = (options_.max_attempts_per_object + 1) * objects;
  robot::PickMemory memory(0.04, options_.max_attempts_per_object);
  std::string status = "completed";
  int attempts = 0;
  while (!run.diverged()) {
    if (exec.time() >= time_limit) {
      status = "time_limit";
      break;
    }
    if (attempts >= max_attempts) {
      status = "attempt_limit";
      break;
    }
    ShowStatus("observing");
    const std::vector<Detection> detections = Observe();
    // Candidates: every described cluster; the undescribed ones still count as neighbours.
    std::vector<robot::ObjectFootprint> footprints;
    for (const auto& d : detections) footprints.push_back(d.footprint);
    robot::PickMemory view = memory;  // This capture's view: undescribed clusters are never picked.
    for (const auto& d : detections) {
      if (!d.category) view.Skip(d.footprint.centre_xy, robot::SkipReason::kUnreachable);
    }
    robot::GraspPlan plan;
    int chosen = -1;
    while (true) {
      const int i = robot::ChooseNextPick(footprints, view);
      if (i < 0) break;
      robot::GraspOptions grasp_options;
      grasp_options.finger_clearance =
          std::max(kMinClearance, std::min(kPerceivedClearance, 0.5 * (robot::kMaxGap - footprints[i].width)));
      plan = robot::PlanTopDownGrasp(footprints[i], exec.ReferenceJoints(), grasp_options);
      if (plan.status == robot::GraspStatus::kOk) {
        chosen = i;
        break;
      }
      memory.Skip(footprints[i].centre_xy, robot::SkipReason::kUnreachable);
      view.Skip(footprints[i].centre_xy, robot::SkipReason::kUnreachable);
      scorer_->Unreachable(i);
      ++skipped_;
      attempts_log_.push_back({{"time_s", exec.time()}, {"category", *detections[i].category},
                               {"xy", {footprints[i].centre_xy.x(), footprints[i].centre_xy.y()}},
                               {"result", std::string("skipped: ") + robot::ToString(plan.status)}});
    }
    if (chosen < 0) break;  // Nothing left that can be picked.

    const Detection& d = detections[chosen];
    const int attempt = memory.RecordAttempt(d.footprint.centre_xy);
    ++attempts;
    ShowStatus("object " + std::to_string(chosen) + ": " + *d.category + " (" + Fixed(d.confidence, 2) + ")  attempt " +
               std::to_string(attempt) + "/" + std::to_string(options_.max_attempts_per_object));
    AttemptRecord record;
    record.detection = chosen;
    record.predicted = *d.category;
    record.confidence = d.confidence;
    record.start_s = exec.time();
    const auto [centre_error, width_error] =
        scorer_->GraspErrors(chosen, d.footprint.centre_xy, d.footprint.width, model_, *data_);
    const std::string result = PickAndSort(d, plan, record);
    record.end_s = exec.time();
    scorer_->Attempt(record);
    if (result == "released") ++released_;
    if (result == "missed") ++missed_;
    if (result == "dropped") ++dropped_;
    if (result == "motion_failed") memory.Skip(d.footprint.centre_xy, robot::SkipReason::kUnreachable);
    attempts_log_.push_back({{"time_s", record.start_s},
                             {"duration_s", record.end_s - record.start_s},
                             {"category", *d.category},
                             {"confidence", d.confidence},
                             {"xy", {d.footprint.centre_xy.x(), d.footprint.centre_xy.y()}},
                             {"pinch_yaw", d.footprint.pinch_yaw},
                             {"width_m", d.footprint.width},
                             {"top_z_m", d.footprint.top_z},
                             {"result", result},
                             {"truth_object", scorer_->ObjectOf(chosen) >= 0 ? nlohmann::json(placed_[scorer_->ObjectOf(chosen)].name) : nlohmann::json(nullptr)},
                             {"truth_centre_error_m", centre_error},
                             {"truth_width_error_m", width_error},
                             {"detail", result == "motion_failed" ? run.failure() : ""}});
    if (result == "sim_diverged") break;
  }
  if (run.diverged()) status = "sim_diverged";
  ShowStatus("episode over: " + status);
  run.Wait("settle_result", kSettleTime);
  if (video_) video_->Close();

  std::vector<std::pair<std::string, int>> bins;
  for (const auto& bin : sim::BinNames(model_)) bins.emplace_back(bin.substr(4), model_.Id(mjOBJ_BODY, bin));
  const nlohmann::json items = scorer_->Items(*data_, bins);
  const double wall = SecondsSince(wall_start);
  int warnings = 0;
  for (int i = 0; i < mjNWARNING; ++i) warnings += (*data_)->warning[i].number;
  const nlohmann::json run_figures = {
      {"status", status},
      {"sim_time_s", exec.time()},
      {"wall_time_s", wall},
      {"real_time_factor", exec.time() / wall},
      {"frames", frames_},
      {"perception_ms_per_frame", frames_ > 0 ? 1000 * perception_wall_s_ / frames_ : 0.0},
      {"render_ms_per_frame", frames_ > 0 ? 1000 * render_wall_s_ / frames_ : 0.0},
      {"video_frames", video_ ? video_->frames() : 0},
      {"video_render_wall_s", video_ ? video_->render_wall_s() : 0.0},
      {"mujoco_warnings", warnings}};
  nlohmann::json metrics = {
      {"seed", options_.seed},
      {"scene", options_.scene.string()},
      {"object_set", set_.source.string()},
      {"model", options_.model.string()},
      {"descriptor", perception::DescriptorName(recognizer_.descriptor)},
      {"variation",
       {{"light_intensity", options_.light_intensity},
        {"noise_scale", options_.noise_scale},
        {"friction_scale", options_.variation.friction_scale},
        {"mass_scale", options_.variation.mass_scale},
        {"camera_shift_m", options_.variation.camera_shift_m},
        {"camera_turn_rad", options_.variation.camera_turn_rad}}},
      {"items", items},
      {"summary", SummarizeEpisode(items, scorer_->attempts(), scorer_->grasps(), run_figures)},
      {"attempts", attempts_log_},
      {"video", options_.video.empty() ? nlohmann::json(nullptr) : nlohmann::json(options_.video.string())}};
  WriteJson(options_.out / "metrics.json", metrics);
  WriteJson(options_.out / "run.json", RunRecord(command_line, options_.seed,
                                                 {{"command", "episode"}, {"scene", options_.scene.string()},
                                                  {"wall_time_s", wall}}));
  return metrics;
}

}  // namespace

nlohmann::json RunEpisode(const EpisodeOptions& options, const std::vector<std::string>& command_line) {
  if (options.max_attempts_per_object < 1) throw std::invalid_argument("--max-attempts: expected at least 1");
  if (!(options.light_intensity > 0)) throw std::invalid_argument("--light-intensity: expected > 0");
  if (!(options.noise_scale >= 0)) throw std::invalid_argument("--noise-scale: expected >= 0");
  if (!std::filesystem::is_regular_file(options.scene)) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': file not found");
  }
  const ObjectSet set = LoadObjectSet(options.object_set);
  const perception::RecognitionModel recognizer = perception::LoadModel(options.model);
  std::set<std::string> categories;
  for (const auto& spec : set.objects) categories.insert(spec.category);
  for (const auto& c : categories) {
    if (std::find(recognizer.classes.begin(), recognizer.classes.end(), c) == recognizer.classes.end()) {
      throw std::invalid_argument("model '" + options.model.string() + "': does not know category '" + c +
                                  "' of object set '" + options.object_set.string() + "'");
    }
  }
  PrepareOutputDir(options.out);
  EpisodeRun run(options, set, recognizer);
  return run.Run(command_line);
}

std::string EpisodeParagraph(const nlohmann::json& metrics) {
  const nlohmann::json& s = metrics["summary"];
  const nlohmann::json& o = s["outcomes"];
  const auto rate = [](const nlohmann::json& v) { return v.is_null() ? std::string("n/a") : Fixed(100 * v.get<double>(), 0) + " %"; };
  std::string text = "Episode (seed " + std::to_string(metrics["seed"].get<uint64_t>()) + ", " +
                     std::to_string(s["items"].get<int>()) + " objects): " + std::to_string(o["sorted"].get<int>()) +
                     " sorted into the right bin (" + rate(s["correct_sort_rate"]) + ")";
  for (const auto& outcome : kOutcomes) {
    if (outcome != "sorted" && o[outcome].get<int>() > 0) text += ", " + std::to_string(o[outcome].get<int>()) + " " + outcome;
  }
  text += ". Recognition accuracy " + rate(s["recognition_accuracy"]) + ", grasp success " +
          rate(s["grasp_success_rate"]) + " of " + std::to_string(s["grasp_attempts"].get<int>()) + " attempts, " +
          (s["mean_cycle_time_s"].is_null() ? std::string("no completed pick") : "mean cycle " + Fixed(s["mean_cycle_time_s"].get<double>(), 1) + " s per item") +
          ". " + Fixed(s["sim_time_s"].get<double>(), 1) + " s simulated in " + Fixed(s["wall_time_s"].get<double>(), 1) +
          " s (real-time factor " + Fixed(s["real_time_factor"].get<double>(), 1) + "), perception " +
          Fixed(s["perception_ms_per_frame"].get<double>(), 0) + " ms per frame over " + std::to_string(s["frames"].get<int>()) +
          " frames, status " + s["status"].get<std::string>() + ".";
  return text;
}

}  // namespace sortcell::app
