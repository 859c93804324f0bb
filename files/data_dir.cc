#include "files/data_dir.h"

#include <cstdlib>

#include "sim/scene_composer.h"

namespace sortcell::files {

std::string DataDir() {
  const char* env = std::getenv("SORTCELL_DATA_DIR");
  return env != nullptr && *env != '\0' ? env : SORTCELL_DEFAULT_DATA_DIR;
}

std::filesystem::path ObjectTexturesDir() {
  return std::filesystem::path(DataDir()) / "models" / "objects" / "textures";
}

sim::Model LoadScene(const std::filesystem::path& scene) {
  return sim::Model::FromFile(scene.string(), sim::ModelTextures(std::filesystem::path(DataDir()) / "models"));
}

}  // namespace sortcell::files
