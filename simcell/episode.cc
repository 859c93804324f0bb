#include "simcell/episode.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>

#include "files/data_dir.h"
#include "files/object_set.h"
#include "files/output_dir.h"
#include "common/seeding.h"
#include "common/wall_clock.h"
#include "simcell/calibration_run.h"
#include "simcell/episode_recorder.h"
#include "simcell/episode_setup.h"
#include "simcell/episode_scoring.h"
#include "simcell/sim_cell.h"
#include "simcell/sim_layout.h"
#include "simcell/sim_rig.h"
#include "cell/layout_check.h"
#include "cell/sorting_policy.h"
#include "perception/descriptor.h"
#include "perception/recognition_model.h"
#include "sim/ground_truth.h"
#include "sim/kinect_camera.h"
#include "sim/object_placement.h"
#include "sim/physics_profile.h"
#include "sim/point_cloud.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {
namespace {

constexpr double kSceneSettleTime = 1.0;  // s, after placing the objects and before scoring
constexpr int kObjectDraws = 20;          // Draws of the episode's objects before "they do not fit".

class EpisodeRun {
 public:
  EpisodeRun(const EpisodeOptions& options, const files::ObjectSet& set, const files::ObjectSet& unknown,
             const perception::RecognitionModel& recognizer)
      : options_(options),
        set_(set),
        unknown_(unknown),
        recognizer_(recognizer),
        rng_(EpisodeRng(options.seed, 0)),
        cell_(files::ReadCellFileOrDefault(options.cell)),
        model_(LoadEpisodeScene(options.scene, WithUnknown(set, unknown), cell_)) {}

  EpisodeMetrics Run(const std::vector<std::string>& command_line);

 private:
  void Calibrate();
  void BuildCell();
  void SelfCalibrate();
  void DrawObjects();
  void PlaceObjects();
  cell::PolicyOptions Budget() const;
  EpisodeMetrics Metrics(const cell::PolicyResult& result, double wall_s) const;
  std::map<std::string, double> WallProfile(double wall_s) const;
  std::map<std::string, double> PhysicsProfile() const;

  const EpisodeOptions& options_;
  const files::ObjectSet& set_;
  const files::ObjectSet& unknown_;  // Objects the model does not know (none without --unknown-set).
  const perception::RecognitionModel& recognizer_;
  std::mt19937_64 rng_;
  files::CellFile cell_;
  sim::Model model_;
  cell::CellLayout layout_;
  cell::CameraCalibration calibration_;
  std::unique_ptr<SimRig> rig_;
  std::optional<CalibrationFigures> calibrated_;
  std::vector<files::ObjectSpec> chosen_;
  std::vector<sim::ObjectShape> shapes_;
  std::vector<sim::TablePose> poses_;
  std::unique_ptr<EpisodeScorer> scorer_;
  std::unique_ptr<EpisodeRecorder> recorder_;
};

// The robot's knowledge of its cell, from the nominal scene: it keeps it when a sweep displaces the camera.
void EpisodeRun::Calibrate() {
  layout_ = ReadCellLayout(model_, cell_);
  if (options_.reject_below) layout_.rules.reject_below = *options_.reject_below;
  calibration_.X_WC = NominalCameraPose(model_, "kinect");
  try {
    cell::CheckRules(layout_, recognizer_.classes);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("cell layout '" + cell_.source.string() + "' with model '" + options_.model.string() +
                                "': " + e.what());
  }
  if (!unknown_.objects.empty() && layout_.rules.reject_bin.empty()) {
    throw std::invalid_argument("cell layout '" + cell_.source.string() + "': unknown objects need a 'reject' bin");
  }
}

// The varied cell, every object stowed out of view, the arm at its observe pose; the empty cell
// captured for background subtraction.
void EpisodeRun::BuildCell() {
  rig_ = std::make_unique<SimRig>(model_, layout_, options_, rng_);
  calibration_.background = rig_->Capture();
}

// The robot's own calibration of its camera, before any object is placed (the arm sweeps the
// workspace); it replaces the nominal pose when the fit succeeds.
void EpisodeRun::SelfCalibrate() {
  if (!SelfCalibrates(options_)) return;
  const cell::HandEyeCalibration result = cell::CalibrateHandEye(rig_->cell(), layout_, calibration_.X_WC);
  calibration_.X_WC = result.X_WC;
  calibrated_ = ScoreCalibration(result, rig_->TrueCameraPose());
  files::WriteJson(options_.out / "calibration.json", CalibrationJson(result, *calibrated_));
}

// The objects: chosen, and where asked or at random non-overlapping poses (drawn before the
// calibration's captures draw their noise, so a seed sets the same scene with or without it).
// A draw of large objects may not fit the table apart (two 0.22 m plates among six produce objects):
// then the objects are drawn again, up to kObjectDraws times (a draw that fits uses the generator as before).
void EpisodeRun::DrawObjects() {
  for (int draw = 1;; ++draw) {
    chosen_ = ChooseObjects(set_, options_, rng_);
    for (auto& spec : ChooseUnknownObjects(unknown_, options_.unknown_objects, rng_))
      chosen_.push_back(std::move(spec));
    shapes_.clear();
    for (const auto& spec : chosen_) shapes_.push_back(sim::ObjectShapeOf(model_, model_.Id(mjOBJ_BODY, spec.name)));
    if (draw == kObjectDraws) break;
    if (auto poses = TryDrawPoses(options_.placements, shapes_, sim::PlacementArea(), options_.placement, rng_)) {
      poses_ = std::move(*poses);
      return;
    }
  }
  poses_ = DrawPoses(options_.placements, shapes_, sim::PlacementArea(), options_.placement, rng_);  // Or says why not.
}

void EpisodeRun::PlaceObjects() {
  const std::vector<files::ObjectSpec>& chosen = chosen_;
  const std::vector<sim::ObjectShape>& shapes = shapes_;
  const std::vector<sim::TablePose>& poses = poses_;
  const std::vector<std::string>& label_names = rig_->kinect().object_names();
  std::vector<PlacedObject> placed;
  std::vector<std::pair<std::string, std::string>> objects_and_bins;
  for (size_t i = 0; i < chosen.size(); ++i) {
    const int body = model_.Id(mjOBJ_BODY, chosen[i].name);
    sim::PlaceObject(model_, rig_->data(), body, poses[i], shapes[i]);
    const int label =
        static_cast<int>(std::find(label_names.begin(), label_names.end(), chosen[i].name) - label_names.begin()) + 1;
    const bool unknown = i >= chosen.size() - static_cast<size_t>(options_.unknown_objects);
    const std::string bin = unknown ? layout_.rules.reject_bin : *layout_.rules.BinOf(chosen[i].category);
    placed.push_back({chosen[i].name, chosen[i].category, body, label, bin, unknown});
    objects_and_bins.emplace_back(chosen[i].name, bin);
  }
  for (const auto& w : BinCapacityWarnings(model_, layout_, objects_and_bins)) {
    spdlog::warn("cell layout '{}': {}", cell_.source.string(), w);
  }
  mj_forward(model_.get(), rig_->data().get());
  scorer_ = std::make_unique<EpisodeScorer>(std::move(placed), static_cast<int>(label_names.size()),
                                            TableExtent{layout_.table_min_xy, layout_.table_max_xy}, layout_.rules);
}

// The policy's budget from the options (the number of objects asked for, not what the scene holds).
cell::PolicyOptions EpisodeRun::Budget() const {
  const int objects = ObjectCount(set_, options_) + options_.unknown_objects;
  cell::PolicyOptions budget;
  budget.pick.max_attempts_per_position = options_.max_attempts_per_object;
  budget.max_attempts = (options_.max_attempts_per_object + 1) * objects;
  budget.time_limit_s = options_.time_limit_s > 0 ? options_.time_limit_s : 60.0 + 45.0 * objects;
  return budget;
}

EpisodeMetrics EpisodeRun::Run(const std::vector<std::string>& command_line) {
  const auto wall_start = WallClock::now();
  Calibrate();
  BuildCell();
  DrawObjects();
  SelfCalibrate();
  PlaceObjects();
  recorder_ = std::make_unique<EpisodeRecorder>(*scorer_, rig_->cell(), model_, rig_->data(), rig_->video(),
                                                options_.seed, options_.max_attempts_per_object, options_.stills);
  recorder_->ShowStatus("settling");
  rig_->cell().Wait("settle", kSceneSettleTime);

  cell::SortingPolicy policy(rig_->cell(), layout_, calibration_, recognizer_, Budget(), recorder_.get());
  const cell::PolicyResult result = policy.Run();
  recorder_->ShowStatus(std::string("episode over: ") + cell::ToString(result.status));
  rig_->cell().Wait("settle_result", kSceneSettleTime);
  if (rig_->video()) rig_->video()->Close();

  const EpisodeMetrics metrics = Metrics(result, SecondsSince(wall_start));
  files::WriteJson(options_.out / "metrics.json", metrics);
  files::WriteJson(options_.out / "run.json", files::RunRecord(command_line, options_.seed,
                                                               {{"command", "episode"},
                                                                {"scene", options_.scene.string()},
                                                                {"wall_time_s", metrics.summary.run.wall_time_s}}));
  return metrics;
}

// Where the episode's wall time went, by stage.
std::map<std::string, double> EpisodeRun::WallProfile(double wall_s) const {
  const sim::CaptureTimings& kinect = rig_->kinect().timings();  // Background capture included.
  std::map<std::string, double> profile{{"physics", rig_->cell().step_wall_s()},
                                        {"kinect_render", kinect.render_s},
                                        {"kinect_noise", kinect.noise_s},
                                        {"label_render", kinect.labels_s},
                                        {"cloud", rig_->cell().cloud_wall_s()},
                                        {"perception", recorder_->perception_wall_s()},
                                        {"video", rig_->video() ? rig_->video()->render_wall_s() : 0.0}};
  double accounted = 0;
  for (const auto& [stage, seconds] : profile) accounted += seconds;
  profile["other"] = wall_s - accounted;
  return profile;
}

std::map<std::string, double> EpisodeRun::PhysicsProfile() const {
  const std::map<std::string, double> stages = sim::PhysicsStageSeconds(rig_->data());
  const ArmExecutor& exec = rig_->cell().executor();
  return {{"collision_s", stages.at("collision")},
          {"constraint_s", stages.at("constraint")},
          {"smooth_s", stages.at("smooth")},
          {"step_s", stages.at("step")},
          {"steps", rig_->data()->timer[mjTIMER_STEP].number},
          {"contacts_per_step", exec.mean_contacts()},
          {"constraint_rows_per_step", exec.mean_constraint_rows()}};
}

EpisodeMetrics EpisodeRun::Metrics(const cell::PolicyResult& result, double wall_s) const {
  RunFigures run;
  run.status = result.status;
  run.sim_time_s = rig_->cell().Now();
  run.wall_time_s = wall_s;
  run.real_time_factor = RealTimeFactor(run.sim_time_s, wall_s);
  run.frames = rig_->cell().frames();
  run.perception_ms_per_frame = run.frames > 0 ? 1000 * recorder_->perception_wall_s() / run.frames : 0.0;
  run.render_ms_per_frame = run.frames > 0 ? 1000 * rig_->cell().render_wall_s() / run.frames : 0.0;
  run.video_frames = rig_->video() ? rig_->video()->frames() : 0;
  run.video_render_wall_s = rig_->video() ? rig_->video()->render_wall_s() : 0.0;
  for (int i = 0; i < mjNWARNING; ++i) run.mujoco_warnings += rig_->data()->warning[i].number;
  run.cycle_phases_s = recorder_->CyclePhases();
  run.cycle_phases_bound_s = recorder_->CyclePhaseBounds();
  run.profile_wall_s = WallProfile(wall_s);
  run.physics_profile = PhysicsProfile();
  run.tracking_max_error_rad = rig_->cell().tracking().max_error;
  run.torque_saturated_samples = rig_->cell().tracking().saturated_samples;
  run.carry_slip_max_mm = recorder_->slip().max_mm;
  run.carry_slip_sum_mm = recorder_->slip().sum_mm;
  run.carries = recorder_->slip().carries;
  run.carry_turn_max_deg = recorder_->slip().max_deg;

  EpisodeMetrics m;
  m.seed = options_.seed;
  m.scene = options_.scene.string();
  m.cell = cell_.source.string();
  m.object_set = set_.source.string();
  m.model = options_.model.string();
  m.descriptor = perception::DescriptorName(recognizer_.descriptor);
  m.variation = {options_.light_intensity,          options_.noise_scale,
                 options_.variation.friction_scale, options_.variation.mass_scale,
                 options_.variation.camera_shift_m, options_.variation.camera_turn_rad,
                 options_.variation.colour_jitter};
  m.items = scorer_->Items(rig_->data(), sim::Bins(model_));
  m.summary = SummarizeEpisode(m.items, scorer_->attempts(), scorer_->grasps(), run);
  m.summary.calibration = calibrated_;
  m.attempts = recorder_->attempts_log();
  if (!options_.video.empty()) m.video = options_.video.string();
  return m;
}

}  // namespace

EpisodeMetrics RunEpisode(const EpisodeOptions& options, const std::vector<std::string>& command_line) {
  if (options.max_attempts_per_object < 1) throw std::invalid_argument("--max-attempts: expected at least 1");
  if (!(options.time_limit_s >= 0)) throw std::invalid_argument("--time-limit: expected >= 0");
  CheckRigOptions(options);
  const files::ObjectSet set = files::LoadObjectSet(options.object_set);
  const files::ObjectSet unknown = LoadUnknownSet(options, set);
  const perception::RecognitionModel recognizer = perception::LoadModel(options.model);
  std::set<std::string> categories;
  for (const auto& spec : set.objects) categories.insert(spec.category);
  for (const auto& c : categories) {
    if (std::find(recognizer.classes.begin(), recognizer.classes.end(), c) == recognizer.classes.end()) {
      throw std::invalid_argument("model '" + options.model.string() + "': does not know category '" + c +
                                  "' of object set '" + options.object_set.string() + "'");
    }
  }
  files::PrepareOutputDir(options.out);
  EpisodeRun run(options, set, unknown, recognizer);
  return run.Run(command_line);
}

}  // namespace sortcell::simcell
