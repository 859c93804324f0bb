#include "app/default_model.h"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include "app/data_dir.h"
#include "app/dataset_capture.h"
#include "app/recognition.h"

namespace sortcell::app {

std::filesystem::path DefaultModelPath(const ObjectSet& set) {
  return std::filesystem::path(DataDir()) / "out" / "models" / (set.name + "-color-cvfh-norm.model.json");
}

std::string DefaultModelHint(const ObjectSet& set) {
  const std::filesystem::path data = std::filesystem::path(DataDir()) / "out" / "models" / (set.name + "_scenes");
  return "make one with --train-if-missing, or: sortcell dataset --objects " + set.source.string() +
         " --scenes 150 --out " + data.string() + " && sortcell train --dataset " + data.string() +
         " --descriptor color-cvfh-norm --out " + DefaultModelPath(set).string();
}

std::filesystem::path EnsureDefaultModel(const ObjectSet& set) {
  const std::filesystem::path path = DefaultModelPath(set);
  if (std::filesystem::exists(path)) return path;
  spdlog::info("no trained model at {}: training one on 150 random scenes of '{}' (about 20 s)", path.string(),
               set.name);
  const std::filesystem::path data = path.parent_path() / (set.name + "_scenes");
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
