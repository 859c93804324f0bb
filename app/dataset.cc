#include "app/dataset.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "app/output_dir.h"

namespace sortcell::app {
namespace {

constexpr const char* kFormat = "sortcell-dataset";

template <typename T>
T Get(const nlohmann::json& json, const std::string& key, const std::string& where) {
  if (!json.is_object() || !json.contains(key)) throw std::invalid_argument(where + ": missing key '" + key + "'");
  try {
    return json.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument(where + ": key '" + key + "' has the wrong type");
  }
}

}  // namespace

const std::string& Dataset::Label(const Sample& s, const std::string& kind) {
  if (kind == "category") return s.category;
  if (kind == "instance") return s.instance;
  throw std::invalid_argument("unknown label kind '" + kind + "' (expected category or instance)");
}

std::vector<std::string> Dataset::Labels(const std::string& kind) const {
  std::vector<std::string> labels;
  for (const Sample& s : samples) {
    const std::string& l = Label(s, kind);
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  }
  return labels;
}

nlohmann::json DescriptorParamsJson(const perception::DescriptorParams& p) {
  const perception::CvfhParams& c = p.cvfh;
  return {{"hsv_min_saturation", p.hsv.min_saturation}, {"hsv_min_value", p.hsv.min_value},
          {"cvfh_voxel_leaf_m", c.voxel_leaf_m}, {"cvfh_normal_radius_m", c.normal_radius_m},
          {"cvfh_eps_angle_rad", c.eps_angle_rad}, {"cvfh_curvature_threshold", c.curvature_threshold},
          {"cvfh_cluster_tolerance_m", c.cluster_tolerance_m}, {"cvfh_min_region_points", c.min_region_points},
          {"cvfh_min_points", c.min_points}};
}

perception::DescriptorParams DescriptorParamsFromJson(const nlohmann::json& j, const std::string& where) {
  perception::DescriptorParams p;
  p.hsv.min_saturation = Get<int>(j, "hsv_min_saturation", where);
  p.hsv.min_value = Get<int>(j, "hsv_min_value", where);
  perception::CvfhParams& c = p.cvfh;
  c.voxel_leaf_m = Get<double>(j, "cvfh_voxel_leaf_m", where);
  c.normal_radius_m = Get<double>(j, "cvfh_normal_radius_m", where);
  c.eps_angle_rad = Get<double>(j, "cvfh_eps_angle_rad", where);
  c.curvature_threshold = Get<double>(j, "cvfh_curvature_threshold", where);
  c.cluster_tolerance_m = Get<double>(j, "cvfh_cluster_tolerance_m", where);
  c.min_region_points = Get<int>(j, "cvfh_min_region_points", where);
  c.min_points = Get<int>(j, "cvfh_min_points", where);
  return p;
}

void SaveDataset(const std::filesystem::path& dir, const Dataset& d) {
  nlohmann::json samples = nlohmann::json::array();
  for (const Sample& s : d.samples) {
    samples.push_back({{"id", s.id}, {"category", s.category}, {"instance", s.instance}, {"source", s.source},
                       {"elevation_deg", s.elevation_deg}, {"frame", s.frame}, {"scene", s.scene},
                       {"cloud", s.cloud}, {"points", s.points}, {"purity", s.purity}, {"iou", s.iou},
                       {"cvfh_regions", s.parts.cvfh_regions}});
  }
  WriteJson(dir / "manifest.json", {{"format", kFormat}, {"version", kDatasetFormatVersion},
                                    {"object_set", d.object_set}, {"views", d.views}, {"seed", d.seed},
                                    {"descriptor_params", DescriptorParamsJson(d.params)}, {"capture", d.capture},
                                    {"samples", samples}});
  const std::filesystem::path csv = dir / "descriptors.csv";
  std::ofstream out(csv);
  out << "id";
  for (int i = 0; i < perception::kHsvBins; ++i) out << ",hsv_" << i;
  for (int i = 0; i < perception::kCvfhBins; ++i) out << ",cvfh_" << i;
  out << "\n";
  out.precision(9);  // Round-trips a float.
  for (const Sample& s : d.samples) {
    out << s.id;
    for (int i = 0; i < perception::kHsvBins; ++i) out << "," << s.parts.hsv[i];
    for (int i = 0; i < perception::kCvfhBins; ++i) out << "," << s.parts.cvfh[i];
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write '" + csv.string() + "'");
}

Dataset LoadDataset(const std::filesystem::path& dir) {
  const std::string where = "dataset '" + dir.string() + "'";
  std::ifstream in(dir / "manifest.json");
  if (!in) throw std::invalid_argument(where + ": no manifest.json (make one with sortcell dataset)");
  nlohmann::json m;
  try {
    in >> m;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(where + ": manifest.json is not valid JSON");
  }
  const std::string mwhere = where + ": manifest.json";
  if (!m.is_object() || m.value("format", "") != kFormat) {
    throw std::invalid_argument(mwhere + " is not a SortCell dataset manifest");
  }
  if (Get<int>(m, "version", mwhere) != kDatasetFormatVersion) {
    throw std::invalid_argument(mwhere + ": format version " + std::to_string(Get<int>(m, "version", mwhere)) +
                                ", this build reads " + std::to_string(kDatasetFormatVersion));
  }
  Dataset d;
  d.object_set = Get<std::string>(m, "object_set", mwhere);
  d.views = Get<int>(m, "views", mwhere);
  d.seed = Get<uint64_t>(m, "seed", mwhere);
  d.params = DescriptorParamsFromJson(Get<nlohmann::json>(m, "descriptor_params", mwhere), mwhere);
  d.capture = m.value("capture", nlohmann::json::object());
  std::map<int, size_t> index_of;
  for (const auto& j : Get<nlohmann::json>(m, "samples", mwhere)) {
    Sample s;
    const std::string swhere = mwhere + " sample";
    s.id = Get<int>(j, "id", swhere);
    s.category = Get<std::string>(j, "category", swhere);
    s.instance = Get<std::string>(j, "instance", swhere);
    s.source = Get<std::string>(j, "source", swhere);
    s.elevation_deg = Get<double>(j, "elevation_deg", swhere);
    s.frame = Get<int>(j, "frame", swhere);
    s.scene = Get<int>(j, "scene", swhere);
    s.cloud = Get<std::string>(j, "cloud", swhere);
    s.points = Get<int>(j, "points", swhere);
    s.purity = Get<double>(j, "purity", swhere);
    s.iou = Get<double>(j, "iou", swhere);
    s.parts.cvfh_regions = Get<int>(j, "cvfh_regions", swhere);
    if (!index_of.emplace(s.id, d.samples.size()).second) {
      throw std::invalid_argument(mwhere + ": duplicate sample id " + std::to_string(s.id));
    }
    d.samples.push_back(std::move(s));
  }

  const std::string cwhere = where + ": descriptors.csv";
  std::ifstream csv(dir / "descriptors.csv");
  if (!csv) throw std::invalid_argument(where + ": no descriptors.csv");
  std::string line;
  std::getline(csv, line);  // header
  const int columns = 1 + perception::kHsvBins + perception::kCvfhBins;
  std::vector<bool> seen(d.samples.size(), false);
  int row = 1;
  while (std::getline(csv, line)) {
    ++row;
    if (line.empty()) continue;
    std::vector<float> values;
    values.reserve(columns);
    const char* p = line.c_str();
    while (*p != '\0') {
      char* end = nullptr;
      const float v = std::strtof(p, &end);
      if (end == p || !std::isfinite(v)) throw std::invalid_argument(cwhere + ": row " + std::to_string(row) + " holds a non-number");
      values.push_back(v);
      p = *end == ',' ? end + 1 : end;
      if (*end != ',' && *end != '\0') throw std::invalid_argument(cwhere + ": row " + std::to_string(row) + " is malformed");
    }
    if (static_cast<int>(values.size()) != columns) {
      throw std::invalid_argument(cwhere + ": row " + std::to_string(row) + " has " + std::to_string(values.size()) +
                                  " columns, expected " + std::to_string(columns));
    }
    const auto it = index_of.find(static_cast<int>(values[0]));
    if (it == index_of.end()) throw std::invalid_argument(cwhere + ": row " + std::to_string(row) + " names an unknown sample");
    Sample& s = d.samples[it->second];
    s.parts.hsv = Eigen::Map<Eigen::VectorXf>(values.data() + 1, perception::kHsvBins);
    s.parts.cvfh = Eigen::Map<Eigen::VectorXf>(values.data() + 1 + perception::kHsvBins, perception::kCvfhBins);
    seen[it->second] = true;
  }
  for (size_t i = 0; i < seen.size(); ++i) {
    if (!seen[i]) throw std::invalid_argument(cwhere + ": no descriptor for sample " + std::to_string(d.samples[i].id));
  }
  return d;
}

}  // namespace sortcell::app
