#include "app/recognition/default_model.h"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <cstdlib>

#include "app/recognition/dataset_capture.h"
#include "app/recognition/recognition.h"

namespace sortcell::app {

namespace {

// The scenes the default model of `set` is trained on, next to the model.
std::filesystem::path DefaultDatasetDir(const ObjectSet& set) { return ModelCacheDir() / (set.name + "_scenes"); }

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
  if (std::filesystem::exists(path)) return path;
  spdlog::info("no trained model at {}: training one on 150 random scenes of '{}' (about 20 s)", path.string(),
               set.name);
  const std::filesystem::path data = DefaultDatasetDir(set);
  SceneOptions scenes;
  const Dataset dataset = CaptureScenes(set, scenes, data);
  SaveDataset(data, dataset);
  const perception::RecognitionModel model = TrainModel(dataset, {}, TrainRequest{});
  const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  perception::SaveModel(temporary, model);
  std::filesystem::rename(temporary, path);
  spdlog::info("trained {} (cross-validation accuracy {:.3f}) and cached it", path.string(), model.cv_accuracy);
  return path;
}

}  // namespace sortcell::app
