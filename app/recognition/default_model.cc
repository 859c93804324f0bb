#include "app/recognition/default_model.h"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include <fstream>

#include "app/common/data_dir.h"
#include "app/recognition/dataset_capture.h"
#include "app/recognition/recognition.h"
#include "sim/kinect_colour.h"
#include "sim/kinect_noise.h"

namespace sortcell::app {

namespace {

// The scenes the default model of `set` is trained on, next to the model.
std::filesystem::path DefaultDatasetDir(const ObjectSet& set) { return ModelCacheDir() / (set.name + "_scenes"); }

// Beside the model (<model>.trained_on): the digest of the object models and the sensor's colour model it
// was trained on, so that a cached model of objects or a sensor that have changed since is trained again.
std::filesystem::path DigestPath(const std::filesystem::path& model) { return model.string() + ".trained_on"; }

// The default model's training scenes of `count` objects: every placement mode the cell meets, some
// objects lying, `per_object` scenes per object (150 for the set's own objects, so that its own objects
// are seen as often with a training variety as without one).
SceneOptions TrainingScenes(size_t count, double scenes_per_object) {
  SceneOptions scenes;
  scenes.modes = {sim::PlacementMode::kSparse, sim::PlacementMode::kDense, sim::PlacementMode::kClustered};
  scenes.placement.lying_fraction = 0.3;
  scenes.scenes = static_cast<int>(std::lround(scenes_per_object * static_cast<double>(count)));
  // A set smaller than a scene's largest count: every scene holds at most all of it.
  scenes.max_objects = std::min<int>(scenes.max_objects, static_cast<int>(count));
  scenes.min_objects = std::min(scenes.min_objects, scenes.max_objects);
  return scenes;
}

// MuJoCo 2.2 draws at most 100 textures in one scene (sim::kMaxTextures): a training variety is
// captured in scenes of its own, in groups of at most this many objects.
constexpr size_t kVarietyGroup = 60;

// The groups of objects captured apart: the set's own, then its variety in groups.
std::vector<ObjectSet> CaptureGroups(const ObjectSet& set) {
  std::vector<ObjectSet> groups{set};
  groups.front().training_variety.clear();
  for (size_t first = 0; first < set.training_variety.size(); first += kVarietyGroup) {
    ObjectSet group;
    group.name = set.name + "_variety" + std::to_string(groups.size());
    group.source = set.source;
    const size_t last = std::min(set.training_variety.size(), first + kVarietyGroup);
    group.objects.assign(set.training_variety.begin() + first, set.training_variety.begin() + last);
    groups.push_back(std::move(group));
  }
  return groups;
}

double ScenesPerObject(const ObjectSet& set) { return 150.0 / static_cast<double>(std::max<size_t>(1, set.objects.size())); }

SceneOptions DefaultTrainingScenes(const ObjectSet& set) { return TrainingScenes(set.objects.size(), ScenesPerObject(set)); }

// Every scene of the recipe, as `sortcell dataset` options.
std::string DefaultTrainingSceneArguments(const ObjectSet& set) {
  std::string text;
  for (const ObjectSet& group : CaptureGroups(set)) {
    const SceneOptions scenes = TrainingScenes(group.objects.size(), ScenesPerObject(set));
    text += (text.empty() ? "" : "; ") + std::string("--scenes ") + std::to_string(scenes.scenes) + " --placement " +
            PlacementModesText(scenes.modes) + " --lying-fraction " + fmt::format("{:g}", scenes.placement.lying_fraction);
  }
  return text;
}

// `part` (captured into `dir`/`sub`) after `whole`: ids, cloud paths and scene numbers made unique.
void AppendDataset(Dataset& whole, Dataset part, const std::string& sub) {
  int scenes = 0;
  for (const Sample& s : whole.samples) scenes = std::max(scenes, s.scene + 1);
  for (Sample& s : part.samples) {
    s.id = static_cast<int>(whole.samples.size());
    s.cloud = sub + "/" + s.cloud;
    if (s.scene >= 0) s.scene += scenes;
    whole.samples.push_back(std::move(s));
  }
  whole.capture["groups"].push_back(part.capture);
}

// How those scenes are segmented (the cell's convex clusters and their settings).
std::string SegmentationDigest() {
  const perception::ConvexClusteringParams c = perception::SegmentationParams().convex;
  return fmt::format("convex {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g} {:g}", c.voxel_m, c.seed_m,
                     c.concavity_deg, c.colour_edge_delta_e, c.colour_edge_concavity_deg, c.colour_importance,
                     c.normal_importance, c.inside_fraction, c.top_tolerance_m, c.hollow_lift_m, c.rim_tolerance_m,
                     c.round_wall_residual, c.cap_fraction, c.cap_overlap_m, c.neck_length_m) +
         fmt::format(" {:g} {:g}", c.lying_elongation, c.round_wall_radius_factor) +
         fmt::format(" creases {:d} {:g} {:g} {:g} {:d} {:g} {:d}", c.split_at_creases, c.crease_radius_m, c.crease_height_m,
                     c.crease_deg, c.crease_rising_neighbours, c.split_link_m, c.split_min_voxels);
}

// What the default model of `set` depends on: its objects' models, the sensor it sees them through, and
// the scenes it is trained on and how they are segmented.
std::string TrainedOnDigest(const ObjectSet& set) {
  return ObjectModelsDigest(set, ObjectTexturesDir()) + " colour " + sim::ToString(sim::KinectColourParams{}) +
         " depth " + sim::DepthJitterText() +
         " scenes " + DefaultTrainingSceneArguments(set) + " segmentation " + SegmentationDigest();
}

std::string ReadDigest(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string digest;
  std::getline(in, digest);
  return digest;
}

}  // namespace

std::filesystem::path ModelCacheDir() {
  const char* env = std::getenv("SORTCELL_MODEL_CACHE");
  if (env != nullptr && *env != '\0') return env;
#ifdef SORTCELL_DEFAULT_MODEL_CACHE
  return SORTCELL_DEFAULT_MODEL_CACHE;
#else
  return std::filesystem::path("out") / "models";
#endif
}

std::filesystem::path DefaultModelPath(const ObjectSet& set) {
  return ModelCacheDir() / (set.name + "-color-cvfh-norm.model.json");
}

std::string DefaultModelHint(const ObjectSet& set) {
  return "make one with --train-if-missing, or: sortcell train --objects " + set.source.string() + " --out " +
         DefaultModelPath(set).string() + " (model cache " + ModelCacheDir().string() +
         "; set SORTCELL_MODEL_CACHE for another folder)";
}

bool DefaultModelIsCurrent(const ObjectSet& set) {
  const std::filesystem::path path = DefaultModelPath(set);
  // A model without a digest beside it was put there by hand (sortcell train): it is the user's.
  return std::filesystem::exists(path) &&
         (!std::filesystem::exists(DigestPath(path)) || ReadDigest(DigestPath(path)) == TrainedOnDigest(set));
}

std::string DefaultRecipeTitle() {
  const SceneOptions scenes = TrainingScenes(1, 150);
  return fmt::format("{} random cell scenes, more in proportion for a training variety ({}; {:g} % lying; seed {}), {}",
                     scenes.scenes, PlacementModesText(scenes.modes), 100 * scenes.placement.lying_fraction, scenes.seed,
                     perception::DescriptorTitle(TrainRequest{}.descriptor));
}

perception::RecognitionModel TrainDefaultRecipe(const ObjectSet& set, const std::filesystem::path& dataset_dir) {
  const std::vector<ObjectSet> groups = CaptureGroups(set);
  Dataset dataset = CaptureScenes(groups.front(), DefaultTrainingScenes(set), dataset_dir);
  for (size_t g = 1; g < groups.size(); ++g) {
    const std::string sub = "variety" + std::to_string(g);
    const SceneOptions scenes = TrainingScenes(groups[g].objects.size(), ScenesPerObject(set));
    AppendDataset(dataset, CaptureScenes(groups[g], scenes, dataset_dir / sub), sub);
  }
  SaveDataset(dataset_dir, dataset);
  return TrainModel(dataset, {}, TrainRequest{});
}

std::filesystem::path EnsureDefaultModel(const ObjectSet& set) {
  const std::filesystem::path path = DefaultModelPath(set);
  const std::string digest = TrainedOnDigest(set);
  if (DefaultModelIsCurrent(set)) return path;
  spdlog::info("{} trained model at {}: training one on random scenes of '{}'{} ({})",
               std::filesystem::exists(path) ? "the objects, the Kinect colour model or the training scenes have changed since the" : "no",
               path.string(), set.name, set.training_variety.empty() ? "" : " and, apart, of its training variety",
               DefaultTrainingSceneArguments(set));
  const perception::RecognitionModel model = TrainDefaultRecipe(set, DefaultDatasetDir(set));
  const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  perception::SaveModel(temporary, model);
  // The model first, its digest last: a run stopped between the two leaves an old digest beside the
  // new model (trained again next time), never a current digest beside an old model.
  const std::filesystem::path digest_temporary = temporary.string() + ".trained_on";
  std::ofstream(digest_temporary) << digest << "\n";
  if (ReadDigest(digest_temporary) != digest) {
    throw std::runtime_error("cannot write '" + digest_temporary.string() + "' (model cache " + ModelCacheDir().string() + ")");
  }
  std::filesystem::rename(temporary, path);
  std::filesystem::rename(digest_temporary, DigestPath(path));
  spdlog::info("trained {} (cross-validation accuracy {:.3f}) and cached it", path.string(), model.cv_accuracy);
  return path;
}

}  // namespace sortcell::app
