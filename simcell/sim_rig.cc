#include "simcell/sim_rig.h"

#include <stdexcept>

#include "common/seeding.h"
#include "simcell/sim_layout.h"
#include "sim/object_placement.h"
#include "sim/physics_profile.h"
#include "sim/point_cloud.h"
#include "sim/scene_variation.h"

namespace sortcell::simcell {

void CheckRigOptions(const EpisodeOptions& options) {
  if (!(options.light_intensity > 0)) throw std::invalid_argument("--light-intensity: expected > 0");
  if (!(options.noise_scale >= 0)) throw std::invalid_argument("--noise-scale: expected >= 0");
  if (!std::filesystem::is_regular_file(options.scene)) {
    throw std::invalid_argument("scene '" + options.scene.string() + "': file not found");
  }
}

std::mt19937_64 KinectNoiseRng(uint64_t seed, uint64_t noise_seed) {
  constexpr uint64_t kKinectStreams = 0x4b1c0000'00000000ULL;  // Apart from the episodes' and the sweeps' streams.
  return EpisodeRng(seed, kKinectStreams + noise_seed);
}

SimRig::SimRig(sim::Model& model, const cell::CellLayout& layout, const EpisodeOptions& options, std::mt19937_64& rng)
    : model_(model), noise_rng_(KinectNoiseRng(options.seed, options.noise_seed)) {
  sim::ApplyVariation(model_, options.variation, rng);
  sim::EnablePhysicsTimers();
  data_ = std::make_unique<sim::Data>(model_);
  kinect_ = std::make_unique<sim::KinectCamera>(model_, "kinect");
  sim::Lighting lighting;
  lighting.intensity = options.light_intensity;
  kinect_->SetLighting(lighting);
  noise_.noise_scale = options.noise_scale;
  const std::vector<std::string> bodies = sim::FreeBodyNames(model_);
  for (size_t i = 0; i < bodies.size(); ++i)
    sim::StowObject(model_, *data_, model_.Id(mjOBJ_BODY, bodies[i]), static_cast<int>(i));
  if (!options.video.empty()) {
    if (options.video.has_parent_path()) std::filesystem::create_directories(options.video.parent_path());
    video_ = std::make_unique<sim::VideoRecorder>(model_, options.video, options.video_options);
  }
  cell_ = std::make_unique<SimCell>(model_, *data_, kinect_.get(), &noise_, &noise_rng_, video_.get(),
                                    layout.control_period);
  cell_->Reset(layout.q_observe, layout.observe_half_gap);
}

perception::Cloud::Ptr SimRig::Capture() {
  return sim::ToOrganizedCloud(kinect_->Capture(*data_, &noise_, &noise_rng_));
}

Eigen::Isometry3d SimRig::TrueCameraPose() const { return NominalCameraPose(model_, "kinect"); }

}  // namespace sortcell::simcell
