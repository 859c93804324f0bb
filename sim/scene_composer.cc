#include "sim/scene_composer.h"

#include <sstream>
#include <stdexcept>

namespace sortcell::sim {
namespace {

constexpr size_t kObjectsInDefaultBuffers = 12;

std::string Include(const std::filesystem::path& file) {
  return "  <include file=\"" + std::filesystem::absolute(file).lexically_normal().string() + "\"/>\n";
}

// MuJoCo cameras look along their -z with +y up: xyaxes = (right, up) of the image.
std::string CameraElement(const CameraSpec& camera) {
  const Eigen::Vector3d forward = (camera.target_W - camera.p_W).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  std::ostringstream xml;
  xml.precision(9);
  xml << "    <camera name=\"" << camera.name << "\" pos=\"" << camera.p_W.transpose() << "\" xyaxes=\""
      << right.transpose() << " " << up.transpose() << "\" fovy=\"49.13\"/>\n";
  return xml.str();
}

}  // namespace

std::vector<Model::VirtualFile> ComposeCell(const std::filesystem::path& models_dir,
                                            const std::vector<std::filesystem::path>& object_models,
                                            const std::vector<CameraSpec>& cameras, const std::string& bins_xml) {
  std::string main = "<mujoco model=\"sortcell_composed\">\n  <compiler angle=\"radian\" autolimits=\"true\"/>\n";
  main += Include(models_dir / "cell" / "cell.inc.xml");
  main += bins_xml.empty() ? Include(models_dir / "cell" / "bins.inc.xml") : "  <include file=\"bins.inc.xml\"/>\n";
  main += Include(models_dir / "gripper" / "gripper.inc.xml");
  main += Include(models_dir / "ur5" / "ur5.inc.xml");
  main += Include(models_dir / "objects" / "objects.inc.xml");
  for (const auto& object : object_models) main += Include(object);
  // MuJoCo's default buffers (100 contacts, 500 constraint rows) hold the cell with a dozen objects;
  // a larger set (e.g. every produce instance at once) gets room for ~4 contacts of 10 rows each.
  if (object_models.size() > kObjectsInDefaultBuffers) {
    main += "  <size nconmax=\"" + std::to_string(100 + 4 * object_models.size()) + "\" njmax=\"" +
            std::to_string(500 + 40 * object_models.size()) + "\"/>\n";
  }
  if (!cameras.empty()) {
    main += "  <worldbody>\n";
    for (const auto& camera : cameras) main += CameraElement(camera);
    main += "  </worldbody>\n";
  }
  main += "</mujoco>\n";
  // The arm's flange includes "flange_tool.inc.xml" from the main file's folder: here, a virtual file.
  std::string tool = "<mujoco>\n" + Include(models_dir / "gripper" / "gripper_body.inc.xml") + "</mujoco>\n";
  std::vector<Model::VirtualFile> files{{"sortcell_composed.xml", main}, {"flange_tool.inc.xml", tool}};
  if (!bins_xml.empty()) files.push_back({"bins.inc.xml", bins_xml});
  return files;
}

std::vector<Model::VirtualFile> ModelTextures(const std::filesystem::path& models_dir) {
  std::vector<Model::VirtualFile> files = Model::AssetFiles(models_dir / "objects" / "textures");
  for (auto& asset : Model::AssetFiles(models_dir / "gripper" / "textures")) files.push_back(std::move(asset));
  return files;
}

Model LoadComposedCell(const std::filesystem::path& models_dir, const std::vector<std::filesystem::path>& object_models,
                       const std::string& name, const std::vector<CameraSpec>& cameras, const std::string& bins_xml) {
  for (const auto& object : object_models) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(object, ec)) {
      throw std::invalid_argument(name + ": object model '" + object.string() + "' not found");
    }
  }
  std::vector<Model::VirtualFile> files = ComposeCell(models_dir, object_models, cameras, bins_xml);
  for (auto& asset : ModelTextures(models_dir)) files.push_back(std::move(asset));
  return Model::FromVirtualFiles(files, name);
}

}  // namespace sortcell::sim
