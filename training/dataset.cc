#include "training/dataset.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "files/json_fields.h"
#include "files/output_dir.h"

namespace sortcell::training {
namespace {

constexpr const char* kFormat = "sortcell-dataset";
constexpr int kCsvColumns = 1 + perception::kHsvBins + perception::kCvfhBins;  // id, HSV, CVFH

// json[key] as a T. @throws std::invalid_argument "<where>: missing key '<key>'" or "... key '<key>' is
// <found>, expected <a T>".
template <typename T>
T Get(const nlohmann::json& json, const std::string& key, const std::string& where) {
  if (!json.is_object() || !json.contains(key)) throw std::invalid_argument(where + ": missing key '" + key + "'");
  const nlohmann::json& value = json.at(key);
  if (!files::JsonHolds<T>(value)) {
    throw std::invalid_argument(where + ": key '" + key + "' is " + files::JsonFound(value) + ", expected " +
                                files::JsonExpectedType<T>());
  }
  return value.get<T>();
}

// manifest.json parsed, its format and version checked.
nlohmann::json ReadManifest(const std::filesystem::path& dir, const std::string& where) {
  std::ifstream in(dir / "manifest.json");
  if (!in) throw std::invalid_argument(where + ": no manifest.json (make one with sortcell dataset)");
  nlohmann::json m;
  try {
    in >> m;
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument(where + ": manifest.json is not valid JSON");
  }
  const std::string mwhere = where + ": manifest.json";
  if (!m.is_object() || !m.contains("format") || m["format"] != kFormat) {
    throw std::invalid_argument(mwhere + " is not a SortCell dataset manifest");
  }
  const int version = Get<int>(m, "version", mwhere);
  if (version != kDatasetFormatVersion && version != 1) {
    throw std::invalid_argument(mwhere + ": format version " + std::to_string(version) + ", this build reads 1 to " +
                                std::to_string(kDatasetFormatVersion));
  }
  return m;
}

Sample SampleFromJson(const nlohmann::json& j, const std::string& where) {
  Sample s;
  s.id = Get<int>(j, "id", where);
  s.category = Get<std::string>(j, "category", where);
  s.instance = Get<std::string>(j, "instance", where);
  s.source = Get<std::string>(j, "source", where);
  s.elevation_deg = Get<double>(j, "elevation_deg", where);
  s.frame = Get<int>(j, "frame", where);
  s.scene = Get<int>(j, "scene", where);
  s.cloud = Get<std::string>(j, "cloud", where);
  s.points = Get<int>(j, "points", where);
  s.purity = Get<double>(j, "purity", where);
  s.iou = Get<double>(j, "iou", where);
  s.parts.cvfh_regions = Get<int>(j, "cvfh_regions", where);
  if (j.contains("fits_familiarity")) s.fits_familiarity = Get<bool>(j, "fits_familiarity", where);
  return s;
}

// The samples of the manifest (descriptor parts still empty), in file order, ids unique.
std::vector<Sample> ReadSamples(const nlohmann::json& m, const std::string& mwhere) {
  const nlohmann::json list = Get<nlohmann::json>(m, "samples", mwhere);
  if (!list.is_array()) throw std::invalid_argument(mwhere + ": key 'samples' is not a list");
  std::vector<Sample> samples;
  std::map<int, size_t> index_of;
  for (size_t k = 0; k < list.size(); ++k) {
    Sample s = SampleFromJson(list[k], mwhere + " samples[" + std::to_string(k) + "]");
    if (!index_of.emplace(s.id, k).second) {
      throw std::invalid_argument(mwhere + ": duplicate sample id " + std::to_string(s.id));
    }
    samples.push_back(std::move(s));
  }
  return samples;
}

// One descriptors.csv row: comma-separated finite numbers.
std::vector<float> ParseCsvRow(const std::string& line, const std::string& where) {
  std::vector<float> values;
  values.reserve(kCsvColumns);
  const char* p = line.c_str();
  while (*p != '\0') {
    char* end = nullptr;
    const float v = std::strtof(p, &end);
    if (end == p || !std::isfinite(v)) throw std::invalid_argument(where + " holds a non-number");
    if (*end != ',' && *end != '\0') throw std::invalid_argument(where + " is malformed");
    values.push_back(v);
    p = *end == ',' ? end + 1 : end;
  }
  if (static_cast<int>(values.size()) != kCsvColumns) {
    throw std::invalid_argument(where + " has " + std::to_string(values.size()) + " columns, expected " +
                                std::to_string(kCsvColumns));
  }
  return values;
}

// Fills every sample's raw descriptor parts from descriptors.csv (one row per sample, by id).
void ReadDescriptors(const std::filesystem::path& dir, const std::string& where, std::vector<Sample>& samples) {
  const std::string cwhere = where + ": descriptors.csv";
  std::ifstream csv(dir / "descriptors.csv");
  if (!csv) throw std::invalid_argument(where + ": no descriptors.csv");
  std::map<int, size_t> index_of;
  for (size_t i = 0; i < samples.size(); ++i) index_of[samples[i].id] = i;
  std::vector<bool> seen(samples.size(), false);
  std::string line;
  std::getline(csv, line);  // header
  for (int row = 2; std::getline(csv, line); ++row) {
    if (line.empty()) continue;
    const std::string rwhere = cwhere + ": row " + std::to_string(row);
    const std::vector<float> values = ParseCsvRow(line, rwhere);
    const auto it = index_of.find(static_cast<int>(values[0]));
    if (it == index_of.end()) throw std::invalid_argument(rwhere + " names an unknown sample");
    Sample& s = samples[it->second];
    s.parts.hsv = Eigen::Map<const Eigen::VectorXf>(values.data() + 1, perception::kHsvBins);
    s.parts.cvfh = Eigen::Map<const Eigen::VectorXf>(values.data() + 1 + perception::kHsvBins, perception::kCvfhBins);
    seen[it->second] = true;
  }
  for (size_t i = 0; i < seen.size(); ++i) {
    if (!seen[i]) throw std::invalid_argument(cwhere + ": no descriptor for sample " + std::to_string(samples[i].id));
  }
}

void WriteDescriptors(const std::filesystem::path& csv, const std::vector<Sample>& samples) {
  errno = 0;
  std::ofstream out(csv);
  out << "id";
  for (int i = 0; i < perception::kHsvBins; ++i) out << ",hsv_" << i;
  for (int i = 0; i < perception::kCvfhBins; ++i) out << ",cvfh_" << i;
  out << "\n";
  out.precision(9);  // Round-trips a float.
  for (const Sample& s : samples) {
    out << s.id;
    for (int i = 0; i < perception::kHsvBins; ++i) out << "," << s.parts.hsv[i];
    for (int i = 0; i < perception::kCvfhBins; ++i) out << "," << s.parts.cvfh[i];
    out << "\n";
  }
  files::CloseChecked(out, csv);
}

}  // namespace

const std::string& Dataset::Label(const Sample& s, perception::LabelKind kind) {
  return kind == perception::LabelKind::kInstance ? s.instance : s.category;
}

std::vector<std::string> Dataset::Labels(perception::LabelKind kind) const {
  std::vector<std::string> labels;
  for (const Sample& s : samples) {
    const std::string& l = Label(s, kind);
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  }
  return labels;
}

nlohmann::json DescriptorParamsJson(const perception::DescriptorParams& params) {
  nlohmann::json json = nlohmann::json::object();
  perception::VisitDescriptorParams(params, [&](const char* key, auto value) { json[key] = value; });
  return json;
}

perception::DescriptorParams DescriptorParamsFromJson(const nlohmann::json& json, const std::string& where) {
  perception::DescriptorParams params;
  perception::VisitDescriptorParams(params, [&](const char* key, auto& value) {
    value = Get<std::remove_reference_t<decltype(value)>>(json, key, where);
  });
  return params;
}

void SaveDataset(const std::filesystem::path& dir, const Dataset& d) {
  nlohmann::json samples = nlohmann::json::array();
  for (const Sample& s : d.samples) {
    samples.push_back({{"id", s.id},
                       {"category", s.category},
                       {"instance", s.instance},
                       {"source", s.source},
                       {"elevation_deg", s.elevation_deg},
                       {"frame", s.frame},
                       {"scene", s.scene},
                       {"cloud", s.cloud},
                       {"points", s.points},
                       {"purity", s.purity},
                       {"iou", s.iou},
                       {"cvfh_regions", s.parts.cvfh_regions},
                       {"fits_familiarity", s.fits_familiarity}});
  }
  files::WriteJson(dir / "manifest.json", {{"format", kFormat},
                                           {"version", kDatasetFormatVersion},
                                           {"object_set", d.object_set},
                                           {"views", d.views},
                                           {"seed", d.seed},
                                           {"descriptor_params", DescriptorParamsJson(d.params)},
                                           {"capture", d.capture},
                                           {"samples", samples}});
  WriteDescriptors(dir / "descriptors.csv", d.samples);
}

Dataset LoadDataset(const std::filesystem::path& dir) {
  const std::string where = "dataset '" + dir.string() + "'";
  const nlohmann::json m = ReadManifest(dir, where);
  const std::string mwhere = where + ": manifest.json";
  Dataset d;
  d.object_set = Get<std::string>(m, "object_set", mwhere);
  d.views = Get<int>(m, "views", mwhere);
  d.seed = Get<uint64_t>(m, "seed", mwhere);
  d.params =
      DescriptorParamsFromJson(Get<nlohmann::json>(m, "descriptor_params", mwhere), mwhere + " descriptor_params");
  d.capture = m.value("capture", nlohmann::json::object());
  d.samples = ReadSamples(m, mwhere);
  ReadDescriptors(dir, where, d.samples);
  return d;
}

}  // namespace sortcell::training
