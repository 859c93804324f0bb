#include "app/objects/object_check.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <random>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "files/data_dir.h"
#include "files/output_dir.h"
#include "assets/image_file.h"
#include "assets/mass_properties.h"
#include "cell/cell_layout.h"
#include "robot/gripper_geometry.h"
#include "sim/arm_io.h"
#include "sim/object_placement.h"
#include "sim/object_shape.h"
#include "sim/offscreen_renderer.h"
#include "sim/scene_composer.h"

namespace sortcell::app {
namespace {

// Where the objects are dropped: the table in front of the robot, clear of the bins.
const Eigen::Vector2d kSpotsMin{0.25, -0.33};
const Eigen::Vector2d kSpotsMax{0.88, 0.33};
constexpr double kSpotGap = 0.03;     // free table between neighbours' footprints (m)
constexpr double kEndWindow = 0.5;    // s: where jitter and the last speeds are watched
constexpr double kCreepWindow = 1.0;  // s
// The soft contact's first impact (it sinks in a few mm and springs back to rest) lasts about this
// long; a bounce is a rise above the resting height after it (s).
constexpr double kImpactTime = 0.03;

// One object's watch while the batch settles.
struct Watch {
  int body = -1;
  int qpos = -1, dof = -1;
  bool touched = false;
  double t_touch = 0;
  double z_highest_after = -1e9;  // once the first impact has passed: where a bounce would show
  bool creep_started = false, jitter_started = false;
  Eigen::Vector3d p_creep_start = Eigen::Vector3d::Zero(), p_jitter_start = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_creep_start = Eigen::Quaterniond::Identity(), q_jitter_start = Eigen::Quaterniond::Identity();
  double end_speed = 0, end_spin = 0, jitter = 0, jitter_rad = 0;
};

struct Rig {
  sim::Model model;
  sim::Data data;
  sim::ArmIo arm;
  int table_geom;
  sim::OffscreenRenderer renderer;  // one for every still: it uploads the set's textures once
  explicit Rig(sim::Model m)
      : model(std::move(m)), data(model), arm(model), table_geom(model.Id(mjOBJ_GEOM, "table_top")), renderer(model) {}

  void HoldArm() {
    arm.SetArmPosition(data, cell::CellLayout().q_observe);
    arm.SetGripperPosition(data, cell::CellLayout().observe_half_gap);
  }
};

// The next objects to drop together: as many of `remaining` (in order) as random non-overlapping
// spots on the table hold, with their spots (seeded: the same set gives the same batches).
std::vector<sim::TablePose> NextBatch(std::vector<size_t>& remaining, const std::vector<sim::ObjectShape>& shapes,
                                      std::vector<size_t>& batch) {
  std::mt19937_64 rng(0);
  for (size_t n = remaining.size(); n >= 1; --n) {
    std::vector<double> radii;
    for (size_t k = 0; k < n; ++k) radii.push_back(shapes[remaining[k]].disc_radius);
    if (auto poses = sim::SampleTablePoses(radii, kSpotsMin, kSpotsMax, kSpotGap, rng)) {
      batch.assign(remaining.begin(), remaining.begin() + static_cast<long>(n));
      remaining.erase(remaining.begin(), remaining.begin() + static_cast<long>(n));
      return *poses;
    }
  }
  batch = {remaining.front()};  // wider than the spots' area: dropped alone in its middle
  remaining.erase(remaining.begin());
  const Eigen::Vector2d middle = (kSpotsMin + kSpotsMax) / 2;
  return {sim::TablePose{middle.x(), middle.y(), 0, false}};
}

bool TouchesTable(const Rig& rig, int body) {
  const mjModel* m = rig.model.get();
  for (int i = 0; i < rig.data->ncon; ++i) {
    const mjContact& c = rig.data->contact[i];
    const int other = c.geom1 == rig.table_geom ? c.geom2 : c.geom2 == rig.table_geom ? c.geom1 : -1;
    if (other >= 0 && m->geom_bodyid[other] == body) return true;
  }
  return false;
}

void Observe(const Rig& rig, double t, const ObjectCheckOptions& options, Watch& w) {
  const double* p = rig.data->qpos + w.qpos;
  const double* v = rig.data->qvel + w.dof;
  if (!w.touched && TouchesTable(rig, w.body)) {
    w.touched = true;
    w.t_touch = t;
  }
  if (w.touched && t > w.t_touch + kImpactTime) w.z_highest_after = std::max(w.z_highest_after, p[2]);
  const Eigen::Vector3d position(p[0], p[1], p[2]);
  const Eigen::Quaterniond orientation(p[3], p[4], p[5], p[6]);
  if (t >= options.settle_s - kCreepWindow && !w.creep_started) {
    w.creep_started = true;
    w.p_creep_start = position;
    w.q_creep_start = orientation;
  }
  if (t >= options.settle_s - kEndWindow) {
    if (!w.jitter_started) {
      w.jitter_started = true;
      w.p_jitter_start = position;
      w.q_jitter_start = orientation;
    }
    w.jitter = std::max(w.jitter, (position - w.p_jitter_start).norm());
    w.jitter_rad = std::max(w.jitter_rad, w.q_jitter_start.angularDistance(orientation));
    w.end_speed = std::max(w.end_speed, Eigen::Vector3d(v[0], v[1], v[2]).norm());
    w.end_spin = std::max(w.end_spin, Eigen::Vector3d(v[3], v[4], v[5]).norm());
  }
}

std::string WhyNot(const ObjectCheckResult& r, const RestLimits& l) {
  std::ostringstream why;
  why.precision(3);
  if (!r.on_table) why << "left the table; ";
  if (r.bounce > l.bounce) why << "bounced " << 1000 * r.bounce << " mm; ";
  if (r.creep > l.creep) why << "crept " << 1000 * r.creep << " mm in the last second; ";
  if (r.turn_deg > l.turn_deg) why << "turned " << r.turn_deg << " deg in the last second; ";
  if (r.jitter > l.jitter || r.jitter_deg > l.jitter_deg) {
    why << "jitters " << 1000 * r.jitter << " mm, " << r.jitter_deg << " deg; ";
  }
  std::string s = why.str();
  return s.empty() ? s : s.substr(0, s.size() - 2);
}

ObjectCheckResult Judge(const Rig& rig, const Watch& w, const files::ObjectSpec& spec, const sim::ObjectShape& shape,
                        const sim::TablePose& spot, const ObjectCheckOptions& options) {
  ObjectCheckResult r;
  r.name = spec.name;
  r.category = spec.category;
  r.import = spec.import;
  const double* p = rig.data->qpos + w.qpos;
  r.p_W_dropped = Eigen::Vector3d(spot.x, spot.y, shape.upright.origin_z + options.drop_height);
  r.p_W_settled = Eigen::Vector3d(p[0], p[1], p[2]);
  const double* R = rig.data->xmat + 9 * w.body;
  r.tilt_deg = std::acos(std::clamp(R[8], -1.0, 1.0)) * 180 / M_PI;
  r.yaw_deg = std::atan2(R[3], R[0]) * 180 / M_PI;
  r.end_speed = w.end_speed;
  r.end_spin = w.end_spin;
  r.creep = (r.p_W_settled - w.p_creep_start).norm();
  const Eigen::Quaterniond q_end(p[3], p[4], p[5], p[6]);
  r.turn_deg = w.q_creep_start.angularDistance(q_end) * 180 / M_PI;
  r.jitter = w.jitter;
  r.jitter_deg = w.jitter_rad * 180 / M_PI;
  r.bounce = w.touched ? std::max(0.0, w.z_highest_after - r.p_W_settled.z()) : 0;
  const cell::CellLayout layout;
  r.on_table = w.touched && p[2] > -0.01 && (r.p_W_settled.head<2>().array() >= layout.table_min_xy.array()).all() &&
               (r.p_W_settled.head<2>().array() <= layout.table_max_xy.array()).all();
  r.why_not = WhyNot(r, options.limits);
  r.rests = r.why_not.empty();
  r.grip_width = assets::MinimumWidth(shape.upright.outline);
  r.graspable = r.grip_width < robot::kMaxGap;
  if (shape.lying) r.grip_width_lying = assets::MinimumWidth(shape.lying->outline);
  return r;
}

// Drops `batch` (indices into the set), each on its spot, and watches them settle.
std::vector<ObjectCheckResult> DropBatch(Rig& rig, const files::ObjectSet& set, const std::vector<int>& bodies,
                                         const std::vector<sim::ObjectShape>& shapes, const std::vector<size_t>& batch,
                                         const std::vector<sim::TablePose>& spots, const ObjectCheckOptions& options) {
  const mjModel* m = rig.model.get();
  mj_resetData(m, rig.data.get());
  rig.HoldArm();
  for (size_t i = 0; i < bodies.size(); ++i) sim::StowObject(rig.model, rig.data, bodies[i], static_cast<int>(i));
  std::vector<Watch> watches;
  for (size_t k = 0; k < batch.size(); ++k) {
    const size_t i = batch[k];
    sim::PlaceObject(rig.model, rig.data, bodies[i], spots[k], shapes[i]);
    Watch w;
    w.body = bodies[i];
    w.qpos = m->jnt_qposadr[m->body_jntadr[w.body]];
    w.dof = m->jnt_dofadr[m->body_jntadr[w.body]];
    rig.data->qpos[w.qpos + 2] += options.drop_height;
    watches.push_back(w);
  }
  mj_forward(m, rig.data.get());
  const int steps = static_cast<int>(std::ceil(options.settle_s / m->opt.timestep));
  for (int s = 1; s <= steps; ++s) {
    rig.HoldArm();
    const sim::StepStatus status = sim::Step(rig.model, rig.data, 1);
    if (status.code == sim::StepStatus::kDiverged) {
      throw std::runtime_error("object set '" + set.source.string() + "': the simulation diverged (" + status.detail +
                               ")");
    }
    for (auto& w : watches) Observe(rig, s * m->opt.timestep, options, w);
  }
  std::vector<ObjectCheckResult> results;
  for (size_t k = 0; k < batch.size(); ++k) {
    results.push_back(Judge(rig, watches[k], set.objects[batch[k]], shapes[batch[k]], spots[k], options));
  }
  return results;
}

void WriteStill(Rig& rig, const std::filesystem::path& file) {
  sim::RenderView view;
  view.camera_id = rig.model.Id(mjOBJ_CAMERA, "review");
  view.width = 1280;
  view.height = 720;
  cv::Mat rgb, bgr;
  rig.renderer.RenderRgb(rig.data, view, rgb);
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  if (!assets::WritePng(file, bgr)) throw std::runtime_error("cannot write '" + file.string() + "'");
}

nlohmann::json ResultJson(const ObjectCheckResult& r) {
  const auto vec = [](const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  nlohmann::json j = {{"name", r.name},
                      {"category", r.category},
                      {"dropped_at_m", vec(r.p_W_dropped)},
                      {"settled_at_m", vec(r.p_W_settled)},
                      {"tilt_deg", r.tilt_deg},
                      {"yaw_deg", r.yaw_deg},
                      {"end_speed_mps", r.end_speed},
                      {"end_spin_radps", r.end_spin},
                      {"creep_m", r.creep},
                      {"turn_deg", r.turn_deg},
                      {"jitter_m", r.jitter},
                      {"jitter_deg", r.jitter_deg},
                      {"bounce_m", r.bounce},
                      {"on_table", r.on_table},
                      {"rests", r.rests},
                      {"why_not", r.why_not},
                      {"grip_width_m", r.grip_width},
                      {"graspable", r.graspable}};
  if (r.grip_width_lying) {
    j["grip_width_lying_m"] = *r.grip_width_lying;
    j["graspable_lying"] = *r.grip_width_lying < robot::kMaxGap;
  }
  if (r.import) {
    j["import"] = {{"source", r.import->source},    {"collision_pieces", r.import->collision_pieces},
                   {"mass_kg", r.import->mass},     {"volume_m3", r.import->volume},
                   {"size_m", vec(r.import->size)}, {"warnings", r.import->warnings}};
  }
  return j;
}

// `text` with every file="<absolute path>" made relative by `relative_to`. MuJoCo 2.2 prefixes every
// file name with the main model's folder, absolute ones too, so a scene on disk names files relatively.
std::string RelativeFiles(const std::string& text,
                          const std::function<std::filesystem::path(const std::filesystem::path&)>& relative_to) {
  static const std::string kKey = "file=\"";
  std::string out;
  size_t from = 0;
  for (size_t at = text.find(kKey); at != std::string::npos; at = text.find(kKey, from)) {
    const size_t start = at + kKey.size(), end = text.find('"', start);
    if (end == std::string::npos) break;
    std::filesystem::path file = text.substr(start, end - start);
    if (file.is_absolute()) file = relative_to(file);
    out += text.substr(from, start - from) + file.string();
    from = end;
  }
  return out + text.substr(from);
}

// A keyframe "checked": the state `data` holds (the first batch at rest), to load in mujoco-simulate.
std::string CheckedKeyframe(const sim::Model& model, const sim::Data& data) {
  std::ostringstream key;
  key.precision(9);
  key << "  <keyframe>\n    <key name=\"checked\" qpos=\"";
  for (int i = 0; i < model->nq; ++i) key << (i ? " " : "") << data->qpos[i];
  key << "\" ctrl=\"";
  for (int i = 0; i < model->nu; ++i) key << (i ? " " : "") << data->ctrl[i];
  key << "\"/>\n  </keyframe>\n";
  return key.str();
}

// The composed scene on disk for mujoco-simulate: the cell's files named from `out`; imported objects'
// fragments copied beside it (their meshes named from `out`, their textures from scenes/, where
// MuJoCo looks for every texture of the cell: texturedir); `keyframe` before its end.
void WriteSceneFiles(const files::ObjectSet& set, const std::filesystem::path& models_dir,
                     const std::filesystem::path& out, const std::filesystem::path& scene,
                     const std::string& keyframe) {
  const std::filesystem::path scenes_dir =
      std::filesystem::absolute(models_dir.parent_path() / "scenes").lexically_normal();
  const std::filesystem::path out_dir = std::filesystem::absolute(out).lexically_normal();
  const auto from_out = [&](const std::filesystem::path& f) { return f.lexically_relative(out_dir); };
  const auto from_scenes = [&](const std::filesystem::path& f) { return f.lexically_relative(scenes_dir); };
  std::vector<std::filesystem::path> fragments;
  std::filesystem::create_directories(out / "objects");
  for (const auto& o : set.objects) {
    if (!o.import) {
      fragments.push_back(o.model);
      continue;
    }
    const std::string text = RelativeFiles(files::ReadTextFile(o.model), [&](const std::filesystem::path& f) {
      return f.extension() == ".png" ? from_scenes(f) : from_out(f);
    });
    fragments.push_back(out_dir / "objects" / (o.name + ".inc.xml"));
    files::WriteTextFile(fragments.back(), text);
  }
  for (auto file : sim::ComposeCell(models_dir, fragments)) {
    file.text = RelativeFiles(file.text, from_out);
    if (file.name != "sortcell_composed.xml") {
      files::WriteTextFile(out / file.name, file.text);
      continue;
    }
    const size_t after_compiler = file.text.find("/>\n") + 3;
    file.text.insert(after_compiler, "  <compiler texturedir=\"" + from_out(scenes_dir).string() + "/\"/>\n");
    file.text.insert(file.text.rfind("</mujoco>"), keyframe);
    files::WriteTextFile(scene, file.text);
  }
}

void WriteCheckJson(const files::ObjectSet& set, const ObjectCheck& check, const std::filesystem::path& out) {
  nlohmann::json objects = nlohmann::json::array();
  for (const auto& r : check.objects) objects.push_back(ResultJson(r));
  nlohmann::json stills = nlohmann::json::array();
  for (const auto& s : check.stills) stills.push_back(s.filename().string());
  files::WriteJson(out / "check.json", {{"object_set", set.source.string()},
                                        {"objects", objects},
                                        {"stills", stills},
                                        {"scene", check.scene.filename().string()}});
}

}  // namespace

ObjectCheck CheckObjects(const files::ObjectSet& set, const std::filesystem::path& out,
                         const ObjectCheckOptions& options) {
  files::PrepareOutputDir(out);
  const std::filesystem::path models_dir = std::filesystem::path(files::DataDir()) / "models";
  std::vector<std::filesystem::path> fragments;
  for (const auto& o : set.objects) fragments.push_back(o.model);
  Rig rig(sim::LoadComposedCell(models_dir, fragments, set.source.string()));
  std::vector<int> bodies;
  std::vector<sim::ObjectShape> shapes;
  std::vector<size_t> remaining;
  for (const auto& o : set.objects) {
    remaining.push_back(bodies.size());
    bodies.push_back(rig.model.Id(mjOBJ_BODY, o.name));
    shapes.push_back(sim::ObjectShapeOf(rig.model, bodies.back()));
  }
  ObjectCheck check;
  std::string keyframe;  // The first batch at rest, as the first still shows it.
  while (!remaining.empty()) {
    std::vector<size_t> batch;
    const std::vector<sim::TablePose> spots = NextBatch(remaining, shapes, batch);
    for (auto& r : DropBatch(rig, set, bodies, shapes, batch, spots, options)) check.objects.push_back(std::move(r));
    if (keyframe.empty()) keyframe = CheckedKeyframe(rig.model, rig.data);
    check.stills.push_back(out / ("objects_" + std::to_string(check.stills.size() + 1) + ".png"));
    WriteStill(rig, check.stills.back());
  }
  check.scene = out / "scene.xml";
  WriteCheckJson(set, check, out);
  WriteSceneFiles(set, models_dir, out, check.scene, keyframe);
  return check;
}

}  // namespace sortcell::app
