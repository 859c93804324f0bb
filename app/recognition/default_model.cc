#include "app/recognition/default_model.h"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <cstdlib>

#include <fstream>

#include "app/common/data_dir.h"
#include "app/recognition/dataset_capture.h"
#include "app/recognition/recognition.h"
#include "sim/kinect_colour.h"

namespace sortcell::app {

namespace {

// The scenes the default model of `set` is trained on, next to the model.
std::filesystem::path DefaultDatasetDir(const ObjectSet& set) { return ModelCacheDir() / (set.name + "_scenes"); }

// Beside the model: the digest of the object models and the sensor's colour model it was trained on,
// so that a cached model of objects or a sensor that have changed since is trained again, not reused.
std::filesystem::path DigestPath(const std::filesystem::path& model) { return model.string() + ".objects"; }

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
  const std::string data = DefaultDatasetDir(set).string();
  return "make one with --train-if-missing, or: sortcell dataset --objects " + set.source.string() +
         " --scenes 150 --out " + data + " && sortcell train --dataset " + data +
         " --descriptor color-cvfh-norm --out " + DefaultModelPath(set).string() +
         " (model cache " + ModelCacheDir().string() + "; set SORTCELL_MODEL_CACHE for another folder)";
}

std::filesystem::path EnsureDefaultModel(const ObjectSet& set) {
  const std::filesystem::path path = DefaultModelPath(set);
  // The sensor the scenes are rendered through counts too.
  const std::string digest = ObjectModelsDigest(set, ObjectTexturesDir()) + " colour " +
                             sim::ToString(sim::KinectColourParams{});
  if (std::filesystem::exists(path) && ReadDigest(DigestPath(path)) == digest) return path;
  spdlog::info("{} trained model at {}: training one on 150 random scenes of '{}' (about 20 s)",
               std::filesystem::exists(path) ? "the objects have changed since the" : "no", path.string(), set.name);
  const std::filesystem::path data = DefaultDatasetDir(set);
  SceneOptions scenes;
  const Dataset dataset = CaptureScenes(set, scenes, data);
  SaveDataset(data, dataset);
  const perception::RecognitionModel model = TrainModel(dataset, {}, TrainRequest{});
  const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  perception::SaveModel(temporary, model);
  std::ofstream(temporary.string() + ".objects") << digest << "\n";
  std::filesystem::rename(temporary.string() + ".objects", DigestPath(path));
  std::filesystem::rename(temporary, path);
  spdlog::info("trained {} (cross-validation accuracy {:.3f}) and cached it", path.string(), model.cv_accuracy);
  return path;
}

}  // namespace sortcell::app
