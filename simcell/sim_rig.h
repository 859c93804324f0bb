#pragma once
/// @file
/// The simulated cell an episode or a calibration runs in: the scene with the options' variations
/// applied, the Kinect with its lighting and noise, the review video, and the cell (sim_cell.h) with
/// the arm at its observe pose and every object stowed out of view.

#include <memory>
#include <random>

#include <Eigen/Geometry>

#include "simcell/episode.h"
#include "simcell/sim_cell.h"
#include "cell/cell_layout.h"
#include "sim/kinect_camera.h"
#include "sim/kinect_noise.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {

/// Checks the options a rig is built from: the lights, the depth noise, the scene file.
/// @throws std::invalid_argument naming the option or the scene.
void CheckRigOptions(const EpisodeOptions& options);

/// The Kinect's noise stream of an episode: realisation `noise_seed` of the sensor's noise over the same
/// scene (0 is the default one; a sweep's `noise_seed` axis draws others, to tell a change's effect
/// from the spread between noise draws).
std::mt19937_64 KinectNoiseRng(uint64_t seed, uint64_t noise_seed);

class SimRig {
 public:
  /// Applies options.variation to `model`, drawing from `rng`. The Kinect's noise draws from a stream of
  /// its own (KinectNoiseRng), so the scene a seed sets does not depend on how the noise draws or on how
  /// many captures came before. `model` must outlive the rig.
  SimRig(sim::Model& model, const cell::CellLayout& layout, const EpisodeOptions& options, std::mt19937_64& rng);
  SimRig(const SimRig&) = delete;
  SimRig& operator=(const SimRig&) = delete;

  sim::Data& data() { return *data_; }
  const sim::Data& data() const { return *data_; }
  SimCell& cell() { return *cell_; }
  const SimCell& cell() const { return *cell_; }
  const sim::KinectCamera& kinect() const { return *kinect_; }
  /// Null when the options ask for no video.
  sim::VideoRecorder* video() { return video_.get(); }
  const sim::VideoRecorder* video() const { return video_.get(); }
  /// A capture of the cell as it stands (the robot's background for subtraction).
  perception::Cloud::Ptr Capture();
  /// Where the Kinect truly is, variations applied (scoring only: the robot never sees it).
  Eigen::Isometry3d TrueCameraPose() const;

 private:
  sim::Model& model_;
  std::mt19937_64 noise_rng_;
  std::unique_ptr<sim::Data> data_;
  std::unique_ptr<sim::KinectCamera> kinect_;
  sim::KinectNoiseParams noise_;
  std::unique_ptr<sim::VideoRecorder> video_;
  std::unique_ptr<SimCell> cell_;
};

}  // namespace sortcell::simcell
