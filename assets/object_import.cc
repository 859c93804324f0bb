#include "assets/object_import.h"

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "assets/image_file.h"
#include "assets/mass_properties.h"
#include "assets/object_geometry.h"
#include "assets/object_xml.h"
#include "assets/urdf_object.h"

namespace sortcell::assets {
namespace {

// Bump when what the importer writes changes: old cache entries are then not reused.
constexpr const char* kImporterVersion = "sortcell-import-3";
// Textures are cut to this many pixels a side: the Kinect sees an object ~100 px wide, and MuJoCo
// decodes and uploads every texture at each scene load (a 4096 px scan texture takes 48 MB).
constexpr int kMaxTextureSide = 1024;
// Densities outside this range (kg/m^3) mean a wrong mass or scale: lighter than foam, denser than lead.
constexpr double kMinDensity = 10, kMaxDensity = 12000;

std::string FileBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The files an import reads: the source, the URDF's meshes, and beside each mesh its materials and images.
std::set<std::filesystem::path> InputFiles(const ObjectSource& source) {
  std::set<std::filesystem::path> files;
  std::vector<std::filesystem::path> meshes;
  if (source.urdf.empty()) {
    meshes.push_back(source.mesh);
  } else {
    files.insert(source.urdf);
    const UrdfObject urdf = ReadUrdfObject(source.urdf);
    for (const auto* shapes : {&urdf.visuals, &urdf.collisions}) {
      for (const auto& s : *shapes) {
        if (s.kind == UrdfShape::Kind::kMesh) meshes.push_back(s.mesh);
      }
    }
  }
  const std::set<std::string> beside{".mtl", ".png", ".jpg", ".jpeg", ".PNG", ".JPG", ".JPEG"};
  for (const auto& mesh : meshes) {
    files.insert(mesh);
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(mesh.parent_path(), ec)) {
      if (entry.is_regular_file(ec) && beside.count(entry.path().extension().string())) files.insert(entry.path());
    }
  }
  return files;
}

void CheckSize(const ObjectSource& source, const Eigen::Vector3d& size, const ImportLimits& limits) {
  const double largest = size.maxCoeff();
  const std::string file = source.file().string();
  std::ostringstream m;
  m.precision(3);
  if (largest > limits.max_size) {
    m << "object '" << source.name << "' from '" << file << "' is " << largest << " m across (expected at most "
      << limits.max_size << " m): is the file in millimetres or centimetres? set scale: 0.001 or 0.01";
    throw std::invalid_argument(m.str());
  }
  if (largest < limits.min_size) {
    m << "object '" << source.name << "' from '" << file << "' is " << largest << " m across (expected at least "
      << limits.min_size << " m): check its units and scale";
    throw std::invalid_argument(m.str());
  }
}

double MassOf(const ObjectSource& source, const std::optional<double>& urdf_mass, double volume,
              std::vector<std::string>& warnings) {
  std::optional<double> mass = source.mass;
  if (!mass) mass = urdf_mass;
  if (!mass && source.density) mass = *source.density * volume;
  const std::string file = source.file().string();
  if (!mass)
    throw std::invalid_argument("object '" + source.name + "' from '" + file + "': no mass (give mass: or density:)");
  if (!std::isfinite(*mass) || *mass <= 0) {
    throw std::invalid_argument("object '" + source.name + "' from '" + file + "': mass must be positive, got " +
                                std::to_string(*mass));
  }
  const double density = *mass / volume;
  if (density < kMinDensity || density > kMaxDensity) {
    warnings.push_back("density " + std::to_string(static_cast<int>(density)) +
                       " kg/m^3 from its mass and collision volume: check the mass and the scale");
  }
  return *mass;
}

// The texture as a PNG MuJoCo 2.2 reads, at most kMaxTextureSide a side.
void ConvertTexture(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(from, ec)) {
    throw std::invalid_argument("texture '" + from.string() + "': file not found (named by the mesh's material)");
  }
  cv::Mat image = ReadImage(from, PixelFormat::kBgr8);
  if (image.empty()) throw std::invalid_argument("texture '" + from.string() + "': does not decode as an image");
  const int side = std::max(image.cols, image.rows);
  if (side > kMaxTextureSide) {
    const double f = static_cast<double>(kMaxTextureSide) / side;
    cv::resize(image, image, cv::Size(), f, f, cv::INTER_AREA);
  }
  if (!WritePng(to, image)) throw std::runtime_error("cannot write '" + to.string() + "'");
}

ImportReport MakeReport(const ObjectSource& source, const ObjectGeometry& g, const MassProperties& m,
                        const ImportLimits& limits) {
  ImportReport r;
  r.name = source.name;
  r.source = source.file().string();
  r.collision_pieces = static_cast<int>(g.hulls.size() + g.primitives.size());
  r.volume = m.volume;
  r.warnings = g.warnings;
  r.mass = MassOf(source, g.urdf_mass, m.volume, r.warnings);
  Eigen::AlignedBox3d box;
  std::vector<Eigen::Vector2d> footprint;
  for (const auto& p : g.CollisionPoints()) {
    box.extend(p);
    footprint.push_back(p.head<2>());
  }
  r.size = box.sizes();
  CheckSize(source, r.size, limits);
  r.com = m.centroid;
  r.principal_inertia = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m.inertia * (r.mass / m.volume)).eigenvalues();
  r.grip_width = MinimumWidth(footprint);
  r.graspable = r.grip_width < limits.max_grip_width;
  if (!r.graspable) {
    std::ostringstream w;
    w.precision(3);
    w << "wider than the gripper's stroke in every direction (" << r.grip_width << " m across, stroke "
      << limits.max_grip_width << " m): it cannot be grasped";
    r.warnings.push_back(w.str());
  }
  return r;
}

nlohmann::json ReportJson(const ImportReport& r) {
  return {{"name", r.name},
          {"source", r.source},
          {"collision_pieces", r.collision_pieces},
          {"volume_m3", r.volume},
          {"mass_kg", r.mass},
          {"size_m", {r.size.x(), r.size.y(), r.size.z()}},
          {"com_m", {r.com.x(), r.com.y(), r.com.z()}},
          {"principal_inertia_kgm2", {r.principal_inertia.x(), r.principal_inertia.y(), r.principal_inertia.z()}},
          {"grip_width_m", r.grip_width},
          {"graspable", r.graspable},
          {"texture", r.texture},
          {"warnings", r.warnings}};
}

Eigen::Vector3d Vec(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

ImportReport ReportFromJson(const nlohmann::json& j) {
  ImportReport r;
  r.name = j.at("name");
  r.source = j.at("source");
  r.collision_pieces = j.at("collision_pieces");
  r.volume = j.at("volume_m3");
  r.mass = j.at("mass_kg");
  r.size = Vec(j.at("size_m"));
  r.com = Vec(j.at("com_m"));
  r.principal_inertia = Vec(j.at("principal_inertia_kgm2"));
  r.grip_width = j.at("grip_width_m");
  r.graspable = j.at("graspable");
  r.texture = j.at("texture");
  r.warnings = j.at("warnings").get<std::vector<std::string>>();
  return r;
}

// `text` into `file`, checked after closing (a full disk is an error, not a short fragment). Written
// here: files/ (WriteTextFile) lies above this library.
void WriteChecked(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write '" + file.string() + "'");
}

// Writes the import into `dir` (a fresh folder).
ImportReport WriteImport(const ObjectSource& source, const ImportLimits& limits, const std::filesystem::path& dir,
                         const std::filesystem::path& final_dir) {
  ObjectGeometry g = ReadObjectGeometry(source, limits);
  g.Recentre();
  const MassProperties unit_density = g.Mass();
  ImportReport report = MakeReport(source, g, unit_density, limits);
  ObjectXmlFiles files{final_dir / "visual.msh", g.texture.empty() ? "" : final_dir / "texture.png"};
  if (!g.texture.empty()) {
    ConvertTexture(g.texture, dir / "texture.png");
    report.texture = g.texture.string();
  }
  if (!g.visual.triangles.empty()) WriteMsh(g.visual, dir / "visual.msh");
  WriteChecked(dir / "object.inc.xml", ObjectXml(source, g, report, unit_density, files));
  WriteChecked(dir / "report.json", ReportJson(report).dump(2) + "\n");
  return report;
}

}  // namespace

std::string SourceDigest(const ObjectSource& source) {
  std::ostringstream key;
  key.precision(17);
  key << kImporterVersion << '\n'
      << source.name << '\n'
      << source.urdf << '\n'
      << source.mesh << '\n'
      << source.scale << '\n'
      << source.mass.value_or(-1) << '\n'
      << source.density.value_or(-1) << '\n'
      << source.friction.value_or(-1);
  std::string content = key.str();
  for (const auto& file : InputFiles(source)) content += '\n' + file.string() + '\n' + FileBytes(file);
  return ContentDigest(content);
}

std::string ContentDigest(const std::string& content) {
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << std::hash<std::string>{}(content);
  return hex.str();
}

ImportedObject ImportObject(const ObjectSource& source, const std::filesystem::path& cache_root,
                            const ImportLimits& limits) {
  const std::filesystem::path dir = cache_root / (source.name + "-" + SourceDigest(source));
  ImportedObject imported;
  imported.fragment = std::filesystem::absolute(dir / "object.inc.xml");
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / "report.json", ec)) {
    try {
      imported.report = ReportFromJson(nlohmann::json::parse(FileBytes(dir / "report.json")));
      imported.from_cache = true;
      return imported;
    } catch (const nlohmann::json::exception&) {
      std::filesystem::remove_all(dir, ec);  // damaged by hand or by a full disk: imported again
    }
  }
  std::filesystem::create_directories(cache_root);
  const std::filesystem::path tmp = cache_root / (".tmp-" + dir.filename().string() + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(tmp, ec);
  std::filesystem::create_directories(tmp);
  try {
    imported.report = WriteImport(source, limits, tmp, std::filesystem::absolute(dir));
  } catch (...) {
    std::filesystem::remove_all(tmp, ec);
    throw;
  }
  std::filesystem::rename(tmp, dir, ec);
  if (ec) std::filesystem::remove_all(tmp, ec);  // another process imported it first: theirs is the same
  return imported;
}

}  // namespace sortcell::assets
