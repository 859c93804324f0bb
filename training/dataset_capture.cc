#include "training/dataset_capture.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

#include "files/data_dir.h"
#include "files/output_dir.h"
#include "files/progress.h"
#include "common/seeding.h"
#include "simcell/segment_labels.h"
#include "cell/cell_layout.h"
#include "perception/pcd_io.h"
#include "perception/segmentation.h"
#include "sim/arm_io.h"
#include "sim/kinect_camera.h"
#include "sim/object_placement.h"
#include "sim/point_cloud.h"
#include "sim/scene_composer.h"
#include "sim/scene_variation.h"

namespace sortcell::training {
namespace {

constexpr double kDeg = M_PI / 180.0;
// Turntable cameras look from 30 degrees left of the Kinect's azimuth (+x): its tripod stands in the
// Kinect's line of sight at low elevations.
constexpr double kTurntableAzimuth = 30 * kDeg;

// A segment with the ground-truth object most of its pixels show (label index into the camera's
// object names, 1-based; 0 = none).
struct LabelledSegment {
  perception::Segment segment;
  int label = 0;
  double purity = 0, iou = 0;
};

sim::Lighting RandomLighting(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> intensity(0.7, 1.3), tilt(-0.2, 0.2);
  sim::Lighting lighting;
  lighting.intensity = intensity(rng);
  lighting.tilt_x = tilt(rng);
  lighting.tilt_y = tilt(rng);
  return lighting;
}

// Scenes being segmented and described on other threads while this one renders the next (CaptureScenes,
// CaptureTurntable). One: on 2 cores, 60 paper scenes took 7.8-8.1 s with one, 7.5-7.8 with two, 7.7-7.8 with three
// (the rendering, with llvmpipe's own threads, is the other half of the work).
constexpr int kCapturesInFlight = 1;

// Captures rendered on this thread (the GL context's) and finished on others, kept in the order they were
// rendered: Add hands over one (its key and the future of its rest) and keeps the oldest once more than
// kCapturesInFlight are out; Finish keeps the rest.
template <typename Key, typename Finished>
class InOrderCaptures {
 public:
  using Keep = std::function<void(const Key&, Finished)>;
  explicit InOrderCaptures(Keep keep) : keep_(std::move(keep)) {}
  void Add(Key key, std::future<Finished> finished) {
    in_flight_.emplace_back(std::move(key), std::move(finished));
    if (static_cast<int>(in_flight_.size()) > kCapturesInFlight) KeepFirst();
  }
  void Finish() {
    while (!in_flight_.empty()) KeepFirst();
  }

 private:
  void KeepFirst() {
    keep_(in_flight_.front().first, in_flight_.front().second.get());
    in_flight_.pop_front();
  }
  Keep keep_;
  std::deque<std::pair<Key, std::future<Finished>>> in_flight_;
};

// A capture rendered (CaptureRig::Render) with what the rest of it needs: the noise and its stream, the
// empty cell's cloud to subtract, the count of objects the label image numbers.
struct PendingCapture {
  sim::KinectFrame clean;
  sim::FrameTruth truth;
  sim::KinectNoiseParams noise;
  std::mt19937_64 rng;
  perception::Cloud::Ptr background;
  int object_count = 0;
};

// A capture's second half (CaptureRig::Render the first), on any thread: the sensor's noise applied (capture.rng goes
// on drawing), the cloud segmented and each segment labelled from the ground truth.
std::vector<LabelledSegment> SegmentCapture(PendingCapture& capture, const perception::SegmentationParams& params,
                                            std::string* failure) {
  const sim::KinectFrame frame =
      sim::KinectCamera::ApplySensorModel(std::move(capture.clean), capture.noise, capture.rng);
  const auto cloud = sim::ToOrganizedCloud(frame);
  perception::SegmentationResult result =
      perception::SegmentObjects(*cloud, capture.truth.X_WC, capture.background.get(), params);
  if (failure != nullptr) *failure = result.detail;
  std::vector<LabelledSegment> out;
  for (auto& segment : result.segments) {
    const simcell::SegmentLabel truth =
        simcell::LabelSegment(capture.truth.labels, segment.indices, capture.object_count);
    LabelledSegment l;
    l.label = truth.label;
    l.purity = truth.purity;
    l.iou = truth.iou;
    l.segment = std::move(segment);
    out.push_back(std::move(l));
  }
  return out;
}

// The cell with the set's objects and extra cameras, every object parked, captures segmented.
class CaptureRig {
 public:
  CaptureRig(const files::ObjectSet& set, const std::vector<sim::CameraSpec>& cameras)
      : model_(Compose(set, cameras)), data_(model_) {
    // Composed cells have no keyframe: put the arm at its observe pose (out of the Kinect's view), open.
    const sim::ArmIo arm(model_);
    arm.SetArmPosition(data_, cell::CellLayout().q_observe);
    arm.SetGripperPosition(data_, cell::CellLayout().observe_half_gap);
    names_ = sim::FreeBodyNames(model_);
    const mjModel* m = model_.get();
    mat_rgba_.assign(m->mat_rgba, m->mat_rgba + 4 * m->nmat);
    geom_rgba_.assign(m->geom_rgba, m->geom_rgba + 4 * m->ngeom);
    for (const auto& spec : set.objects) body_[spec.name] = model_.Id(mjOBJ_BODY, spec.name);
    ParkAll();
  }

  const sim::Model& model() const { return model_; }
  sim::Data& data() { return data_; }
  int Body(const std::string& name) const { return body_.at(name); }
  const std::vector<std::string>& object_names() const { return names_; }

  void ParkAll() {
    int slot = 0;
    for (const auto& [name, body] : body_) sim::ParkObject(model_, data_, body, slot++);
    mj_forward(model_.get(), data_.get());
  }

  // The objects' own colours, then varied at `jitter` (0: left as they are).
  void JitterColours(double jitter, std::mt19937_64& rng) {
    mjModel* m = model_.mutable_get();
    std::copy(mat_rgba_.begin(), mat_rgba_.end(), m->mat_rgba);
    std::copy(geom_rgba_.begin(), geom_rgba_.end(), m->geom_rgba);
    if (jitter > 0) sim::JitterObjectColours(model_, jitter, rng);
  }

  sim::KinectCamera& Camera(const std::string& name) {
    auto& camera = cameras_[name];
    if (!camera) camera = std::make_unique<sim::KinectCamera>(model_, name);
    return *camera;
  }

  // The empty cell seen by `camera` (objects parked, noise on), for background subtraction.
  void CaptureBackground(const std::string& camera, std::mt19937_64& rng) {
    ParkAll();
    const sim::KinectNoiseParams noise;
    background_[camera] = sim::ToOrganizedCloud(Camera(camera).Capture(data_, &noise, &rng));
  }

  // A capture's first half, on this thread (the GL context's): the current state rendered under lighting
  // and a camera colour drawn from `rng`, the noise still to apply from where `rng` stands (SegmentCapture
  // finishes it on any thread; a capture that cannot be segmented has no segments, and says why).
  PendingCapture Render(const std::string& camera, std::mt19937_64& rng, double noise_scale) {
    mj_forward(model_.get(), data_.get());
    sim::KinectCamera& kinect = Camera(camera);
    kinect.SetLighting(RandomLighting(rng));
    // Every dataset capture (turntable and scenes alike) varies the camera's colour, so a model does not
    // learn one exact exposure, and a test set is seen through varied cameras too.
    PendingCapture capture;
    capture.noise.colour = sim::JitterColour(capture.noise.colour, rng);
    capture.noise.noise_scale = noise_scale;
    capture.clean = kinect.RenderClean(data_, &capture.truth);  // Training labels: the true pose and label image.
    capture.rng = rng;
    capture.background = background_.at(camera);
    capture.object_count = static_cast<int>(names_.size());
    return capture;
  }

 private:
  static sim::Model Compose(const files::ObjectSet& set, const std::vector<sim::CameraSpec>& cameras) {
    std::vector<std::filesystem::path> models;
    for (const auto& spec : set.objects) models.push_back(spec.model);
    return sim::LoadComposedCell(std::filesystem::path(files::DataDir()) / "models", models, set.source.string(),
                                 cameras);
  }

  sim::Model model_;
  sim::Data data_;
  std::vector<std::string> names_;
  std::map<std::string, int> body_;
  std::map<std::string, std::unique_ptr<sim::KinectCamera>> cameras_;
  std::map<std::string, perception::Cloud::Ptr> background_;
  std::vector<float> mat_rgba_, geom_rgba_;  // The objects' own colours, for JitterColours.
};

// A labelled segment with its descriptor's parts computed: writes its cloud as sample.id's and fills
// `sample`; false (with the reason) when it could not be described.
bool KeepDescribed(const LabelledSegment& l, perception::DescriptorParts parts, const std::filesystem::path& dir,
                   Sample& sample, std::string& reason) {
  sample.parts = std::move(parts);
  if (sample.parts.status != perception::DescriptorStatus::kOk) {
    reason = sample.parts.detail;
    return false;
  }
  const std::string name = fmt::format("clouds/{:06}.pcd", sample.id);
  perception::SaveCloud(dir / name, *l.segment.cloud_C);
  sample.cloud = name;
  sample.points = static_cast<int>(l.segment.cloud_C->size());
  sample.purity = l.purity;
  sample.iou = l.iou;
  return true;
}

// The segment with the points beyond a random straight edge across the view dropped: a nearer object's
// silhouette, as seen in scenes, hiding 15-70 % of the object. The edge runs in the image plane (points
// compared by x/z, y/z along a random direction); what is kept is the near side of the edge.
LabelledSegment OccludedCopy(const LabelledSegment& l, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), keep(0.30, 0.85);
  const double a = angle(rng), fraction = keep(rng);
  const perception::Cloud& cloud = *l.segment.cloud_C;
  std::vector<double> along;
  along.reserve(cloud.size());
  for (const auto& p : cloud) along.push_back((std::cos(a) * p.x + std::sin(a) * p.y) / p.z);
  std::vector<double> sorted = along;
  const size_t cut = static_cast<size_t>(fraction * (sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + cut, sorted.end());
  const double edge = sorted[cut];
  LabelledSegment occluded = l;
  occluded.segment.cloud_C.reset(new perception::Cloud);
  occluded.segment.indices.clear();
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (along[i] > edge) continue;
    occluded.segment.cloud_C->push_back(cloud[i]);
    if (i < l.segment.indices.size()) occluded.segment.indices.push_back(l.segment.indices[i]);
  }
  occluded.iou = l.iou * static_cast<double>(occluded.segment.cloud_C->size()) / std::max<size_t>(1, cloud.size());
  return occluded;
}

void PrepareDatasetDir(const std::filesystem::path& dir) {
  files::PrepareOutputDir(dir);
  std::filesystem::create_directories(dir / "clouds");
}

// The rig's label of object `name` (1-based: 0 is everything else).
int LabelOf(const CaptureRig& rig, const std::string& name) {
  const auto& names = rig.object_names();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin()) + 1;
}

// One camera per elevation, all aimed at the turntable's middle.
std::vector<sim::CameraSpec> TurntableCameras(const TurntableOptions& options) {
  std::vector<sim::CameraSpec> cameras;
  const Eigen::Vector3d aim = options.centre_W + Eigen::Vector3d(0, 0, options.aim_height_m);
  for (double e : options.elevations_deg) {
    // From the Kinect's side of the table, so the robot stays behind the turntable, outside the box.
    const Eigen::Vector3d direction(std::cos(e * kDeg) * std::cos(kTurntableAzimuth),
                                    std::cos(e * kDeg) * std::sin(kTurntableAzimuth), std::sin(e * kDeg));
    cameras.push_back({"turntable_" + std::to_string(static_cast<int>(e)), aim + options.distance_m * direction, aim});
  }
  return cameras;
}

// Where a turntable view comes from: the object, the camera and its elevation, the view's place in the
// revolution and in the whole capture (its random stream).
struct TurntableView {
  const files::ObjectSpec& spec;
  const std::string& camera;
  double elevation_deg = 0;
  int view = 0;
  uint64_t index = 0;
};

// A turntable view's capture finished off the GL thread: the object's best segment (none: `failure`, or
// "no segment of the object") with its descriptor's parts, and its occluded copies with theirs.
struct SegmentedView {
  std::optional<LabelledSegment> best;
  perception::DescriptorParts parts;
  std::string failure;
  std::vector<std::pair<LabelledSegment, perception::DescriptorParts>> occluded;
};

// The second stage of a turntable view (any thread): noise, segmentation, the object's segment and its
// descriptor, then its occluded copies drawn from the view's stream where the noise left it.
SegmentedView SegmentView(PendingCapture capture, int label, int occluded_copies,
                          const perception::DescriptorParams& descriptor) {
  SegmentedView view;
  std::vector<LabelledSegment> segments = SegmentCapture(capture, {}, &view.failure);
  for (auto& l : segments) {
    if (l.label == label && (!view.best || l.iou > view.best->iou)) view.best = std::move(l);
  }
  if (!view.best) return view;
  view.parts = perception::ComputeDescriptorParts(*view.best->segment.cloud_C, descriptor);
  if (view.parts.status != perception::DescriptorStatus::kOk) return view;
  for (int k = 0; k < occluded_copies; ++k) {
    LabelledSegment copy = OccludedCopy(*view.best, capture.rng);
    perception::DescriptorParts parts = perception::ComputeDescriptorParts(*copy.segment.cloud_C, descriptor);
    view.occluded.emplace_back(std::move(copy), std::move(parts));
  }
  return view;
}

// The first stage of a turntable view (this thread): the object alone on the turntable, jittered, and
// rendered; the rest on another thread (SegmentView).
std::future<SegmentedView> RenderTurntableView(CaptureRig& rig, const TurntableOptions& options, const TurntableView& v,
                                               const perception::DescriptorParams& descriptor) {
  std::mt19937_64 rng = EpisodeRng(options.seed, v.index);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  rig.ParkAll();
  const double yaw = 2 * M_PI * v.view / options.views + options.yaw_jitter_rad * unit(rng);
  // One draw per statement (arguments are evaluated in an unspecified order): y first, as GCC did.
  const double dy = options.jitter_m * unit(rng);
  const double dx = options.jitter_m * unit(rng);
  sim::PlaceObject(rig.model(), rig.data(), rig.Body(v.spec.name), options.centre_W.x() + dx, options.centre_W.y() + dy,
                   yaw);
  PendingCapture capture = rig.Render(v.camera, rng, 1);
  return std::async(std::launch::async, SegmentView, std::move(capture), LabelOf(rig, v.spec.name),
                    options.occluded_copies, descriptor);
}

// A view's sample (with its occluded copies) kept, ids in order and clouds written, or the view put into
// `skipped` with the reason.
void KeepTurntableView(const TurntableView& v, SegmentedView segmented, const std::filesystem::path& dir,
                       Dataset& dataset, nlohmann::json& skipped) {
  Sample sample;
  sample.id = static_cast<int>(dataset.samples.size());
  sample.category = v.spec.category;
  sample.instance = v.spec.instance;
  sample.source = "turntable";
  sample.elevation_deg = v.elevation_deg;
  sample.frame = v.view;
  std::string reason = segmented.failure.empty() ? "no segment of the object" : segmented.failure;
  if (!segmented.best || !KeepDescribed(*segmented.best, std::move(segmented.parts), dir, sample, reason)) {
    skipped.push_back(
        {{"instance", v.spec.instance}, {"elevation_deg", v.elevation_deg}, {"frame", v.view}, {"reason", reason}});
    return;
  }
  dataset.samples.push_back(sample);
  for (auto& [copy, parts] : segmented.occluded) {
    Sample occluded = sample;
    occluded.id = static_cast<int>(dataset.samples.size());
    occluded.source = "turntable_occluded";
    std::string why;  // An occluded copy too small to describe is left out; the view is not.
    if (KeepDescribed(copy, std::move(parts), dir, occluded, why)) dataset.samples.push_back(std::move(occluded));
  }
}

}  // namespace

Dataset CaptureTurntable(const files::ObjectSet& set, const TurntableOptions& options,
                         const std::filesystem::path& dir) {
  if (options.views < 3) throw std::invalid_argument("--views: expected at least 3 views per revolution");
  PrepareDatasetDir(dir);
  const std::vector<sim::CameraSpec> cameras = TurntableCameras(options);
  CaptureRig rig(set, cameras);
  Dataset dataset;
  dataset.object_set = set.source.string();
  dataset.views = options.views;
  dataset.seed = options.seed;
  nlohmann::json skipped = nlohmann::json::array();
  std::mt19937_64 background_rng = EpisodeRng(options.seed, 0xbac0);
  for (const auto& camera : cameras) rig.CaptureBackground(camera.name, background_rng);

  const int total = static_cast<int>(set.objects.size() * cameras.size()) * options.views;
  files::Progress progress("dataset " + set.name, total);
  // Two stages, as for scenes (CaptureScenes): this thread renders the next view while another segments
  // and describes the last; the samples are kept in the views' order.
  InOrderCaptures<TurntableView, SegmentedView> captures([&](const TurntableView& v, SegmentedView segmented) {
    KeepTurntableView(v, std::move(segmented), dir, dataset, skipped);
    progress.Advance();
  });
  uint64_t index = 0;
  for (const auto& spec : set.objects) {
    for (size_t c = 0; c < cameras.size(); ++c) {
      for (int view = 0; view < options.views; ++view, ++index) {
        const TurntableView v{spec, cameras[c].name, options.elevations_deg[c], view, index};
        captures.Add(v, RenderTurntableView(rig, options, v, dataset.params));
      }
    }
  }
  captures.Finish();
  progress.Finish();
  dataset.capture = {{"kind", "turntable"},
                     {"captures", total},
                     {"samples", dataset.samples.size()},
                     {"skipped", skipped},
                     {"elevations_deg", options.elevations_deg},
                     {"distance_m", options.distance_m},
                     {"jitter_m", options.jitter_m},
                     {"occluded_copies", options.occluded_copies}};
  return dataset;
}

std::string PlacementModesText(const std::vector<sim::PlacementMode>& modes) {
  std::string text;
  for (const sim::PlacementMode mode : modes) text += (text.empty() ? "" : ",") + std::string(sim::ToString(mode));
  return text;
}

namespace {

// What a scene capture counted: objects placed, objects no segment was of, segments of no object,
// segments too small to describe.
struct SceneTally {
  int placed = 0, missed = 0, spurious = 0, undescribed = 0;
};

// Scene `scene`'s objects drawn and placed at random; returns their indices in the set. Large objects (a
// user's cereal boxes and bleach bottles) may not all fit: the scene then holds as many of those drawn as
// do, the last drawn left out first.
std::vector<int> PlaceRandomScene(CaptureRig& rig, const files::ObjectSet& set,
                                  const std::vector<sim::ObjectShape>& shapes, const SceneOptions& options, int scene,
                                  std::mt19937_64& rng) {
  std::vector<int> order(set.objects.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  int count = std::uniform_int_distribution<int>(options.min_objects, options.max_objects)(rng);
  sim::PlacementOptions placement = options.placement;
  placement.mode = options.modes[scene % options.modes.size()];
  std::vector<sim::ObjectShape> chosen_shapes;
  std::optional<std::vector<sim::TablePose>> poses;
  for (; count >= 1; --count) {
    order.resize(count);
    chosen_shapes.clear();
    for (int o : order) chosen_shapes.push_back(shapes[o]);
    poses = sim::SampleClutter(chosen_shapes, {}, options.area, placement, rng);
    if (poses) break;
  }
  if (!poses) throw std::invalid_argument("scene " + std::to_string(scene) + ": not even one object fits the area");
  rig.ParkAll();
  for (int k = 0; k < count; ++k) {
    sim::PlaceObject(rig.model(), rig.data(), rig.Body(set.objects[order[k]].name), (*poses)[k], chosen_shapes[k]);
  }
  return order;
}

// A scene's capture finished off the GL thread: its segments, each with its descriptor's parts.
struct SegmentedScene {
  std::vector<LabelledSegment> segments;
  std::vector<perception::DescriptorParts> parts;
};

// The second stage of a scene's capture (any thread): noise, segmentation, labels and descriptors.
SegmentedScene SegmentAndDescribe(PendingCapture capture, const perception::SegmentationParams& segmentation,
                                  const perception::DescriptorParams& descriptor) {
  SegmentedScene scene;
  scene.segments = SegmentCapture(capture, segmentation, nullptr);
  for (const auto& l : scene.segments) {
    scene.parts.push_back(l.label == 0 ? perception::DescriptorParts{}
                                       : perception::ComputeDescriptorParts(*l.segment.cloud_C, descriptor));
  }
  return scene;
}

// The scene's segments kept as samples (ids in order, clouds written); the objects of `placed` no segment
// was of counted missed.
void AddSceneSamples(const CaptureRig& rig, const files::ObjectSet& set, SegmentedScene segmented,
                     const std::vector<int>& placed, int scene, const std::filesystem::path& dir, Dataset& dataset,
                     SceneTally& tally) {
  std::vector<bool> found(rig.object_names().size() + 1, false);
  const std::vector<LabelledSegment>& segments = segmented.segments;
  for (size_t i = 0; i < segments.size(); ++i) {
    const LabelledSegment& l = segments[i];
    if (l.label == 0) {
      ++tally.spurious;
      continue;
    }
    const files::ObjectSpec& spec = set.Find(rig.object_names()[l.label - 1]);
    found[l.label] = true;
    Sample sample;
    sample.id = static_cast<int>(dataset.samples.size());
    sample.category = spec.category;
    sample.instance = spec.instance;
    sample.source = "scene";
    sample.elevation_deg = 45;
    sample.frame = static_cast<int>(i);
    sample.scene = scene;
    std::string reason;
    if (KeepDescribed(l, std::move(segmented.parts[i]), dir, sample, reason)) {
      dataset.samples.push_back(std::move(sample));
    } else {
      ++tally.undescribed;
    }
  }
  for (int o : placed) tally.missed += !found[LabelOf(rig, set.objects[o].name)];
}

// Scene `scene`'s depth noise factor, from a stream of its own (the scene is what it is at any factor).
double DepthNoiseScale(const SceneOptions& options, int scene) {
  if (options.depth_noise_max <= 1) return 1;
  std::mt19937_64 rng = EpisodeRng(options.seed, 0xD0100000ull + static_cast<uint64_t>(scene));
  return std::uniform_real_distribution<double>(1.0, options.depth_noise_max)(rng);
}

}  // namespace

Dataset CaptureScenes(const files::ObjectSet& set, const SceneOptions& options, const std::filesystem::path& dir) {
  if (options.modes.empty()) throw std::invalid_argument("scene capture: no placement mode given");
  if (options.min_objects < 1 || options.max_objects < options.min_objects ||
      options.max_objects > static_cast<int>(set.objects.size())) {
    throw std::invalid_argument("scene object count range [" + std::to_string(options.min_objects) + ", " +
                                std::to_string(options.max_objects) + "] does not fit the set's " +
                                std::to_string(set.objects.size()) + " objects");
  }
  PrepareDatasetDir(dir);
  CaptureRig rig(set, {});
  Dataset dataset;
  dataset.object_set = set.source.string();
  dataset.seed = options.seed;
  std::mt19937_64 background_rng = EpisodeRng(options.seed, 0xbac0);
  rig.CaptureBackground("kinect", background_rng);
  std::vector<sim::ObjectShape> shapes;
  for (const auto& spec : set.objects) shapes.push_back(sim::ObjectShapeOf(rig.model(), rig.Body(spec.name)));

  // Two stages: this thread places and renders scene k + 1 (the GL context is this thread's) while
  // another applies the noise to scene k, segments and describes it. Each scene draws from its own
  // stream, so the samples are those of one scene after the other, and are kept in that order.
  SceneTally tally;
  files::Progress progress("scenes " + set.name, options.scenes);
  perception::SegmentationParams segmentation;
  segmentation.clustering = options.clustering;
  struct PlacedScene {
    int scene = 0;
    std::vector<int> placed;
  };
  InOrderCaptures<PlacedScene, SegmentedScene> captures([&](const PlacedScene& p, SegmentedScene segmented) {
    AddSceneSamples(rig, set, std::move(segmented), p.placed, p.scene, dir, dataset, tally);
    progress.Advance();
  });
  for (int scene = 0; scene < options.scenes; ++scene) {
    std::mt19937_64 rng = EpisodeRng(options.seed, static_cast<uint64_t>(scene));
    PlacedScene next{scene, PlaceRandomScene(rig, set, shapes, options, scene, rng)};
    tally.placed += static_cast<int>(next.placed.size());
    if (options.colour_jitter > 0) {
      // A stream of its own: the scene's objects, poses and camera are what they are without jitter.
      std::mt19937_64 colours = EpisodeRng(options.seed, 0xC0100000ull + static_cast<uint64_t>(scene));
      rig.JitterColours(std::uniform_real_distribution<double>(0.0, options.colour_jitter)(colours), colours);
    }
    PendingCapture capture = rig.Render("kinect", rng, DepthNoiseScale(options, scene));
    captures.Add(std::move(next),
                 std::async(std::launch::async, SegmentAndDescribe, std::move(capture), segmentation, dataset.params));
  }
  captures.Finish();
  progress.Finish();
  for (Sample& s : dataset.samples) s.fits_familiarity = options.fits_familiarity;
  dataset.capture = {{"kind", "scenes"},
                     {"scenes", options.scenes},
                     {"objects_placed", tally.placed},
                     {"objects_not_segmented", tally.missed},
                     {"segments_without_object", tally.spurious},
                     {"segments_not_described", tally.undescribed},
                     {"samples", dataset.samples.size()},
                     {"objects_per_scene", {options.min_objects, options.max_objects}},
                     {"placement", PlacementModesText(options.modes)},
                     {"lying_fraction", options.placement.lying_fraction},
                     {"colour_jitter", options.colour_jitter},
                     {"depth_noise_max", options.depth_noise_max},
                     {"fits_familiarity", options.fits_familiarity}};
  return dataset;
}

}  // namespace sortcell::training
