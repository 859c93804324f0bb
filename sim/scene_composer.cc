#include "sim/scene_composer.h"

#include <stdexcept>

namespace sortcell::sim {
namespace {

std::string Include(const std::filesystem::path& file) {
  return "  <include file=\"" + std::filesystem::absolute(file).lexically_normal().string() + "\"/>\n";
}

}  // namespace

std::vector<Model::VirtualFile> ComposeCell(const std::filesystem::path& models_dir,
                                            const std::vector<std::filesystem::path>& object_models) {
  std::string main = "<mujoco model=\"sortcell_composed\">\n  <compiler angle=\"radian\" autolimits=\"true\"/>\n";
  main += Include(models_dir / "cell" / "cell.inc.xml");
  main += Include(models_dir / "gripper" / "gripper.inc.xml");
  main += Include(models_dir / "ur5" / "ur5.inc.xml");
  main += Include(models_dir / "objects" / "objects.inc.xml");
  for (const auto& object : object_models) main += Include(object);
  main += "</mujoco>\n";
  // The arm's flange includes "flange_tool.inc.xml" from the main file's folder: here, a virtual file.
  std::string tool = "<mujoco>\n" + Include(models_dir / "gripper" / "gripper_body.inc.xml") + "</mujoco>\n";
  return {{"sortcell_composed.xml", main}, {"flange_tool.inc.xml", tool}};
}

Model LoadComposedCell(const std::filesystem::path& models_dir,
                       const std::vector<std::filesystem::path>& object_models, const std::string& name) {
  for (const auto& object : object_models) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(object, ec)) {
      throw std::invalid_argument(name + ": object model '" + object.string() + "' not found");
    }
  }
  return Model::FromVirtualFiles(ComposeCell(models_dir, object_models), name);
}

}  // namespace sortcell::sim
