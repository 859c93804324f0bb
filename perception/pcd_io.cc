#include "perception/pcd_io.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <utility>
#include <stdexcept>
#include <string>

namespace sortcell::perception {
namespace {

bool HasField(const pcl::PCLPointCloud2& blob, const std::string& name) {
  return std::any_of(blob.fields.begin(), blob.fields.end(),
                     [&](const pcl::PCLPointField& f) { return f.name == name; });
}

// DATA binary_compressed starts with the compressed and the uncompressed sizes, which PCL allocates
// before it checks them: the uncompressed must be what the header's points take, the compressed must
// be in the file.
void CheckCompressedSizes(const std::string& bytes, unsigned int data_start, double claimed_bytes,
                          const std::string& where) {
  uint32_t sizes[2] = {0, 0};
  if (data_start + 8.0 <= bytes.size()) std::memcpy(sizes, bytes.data() + data_start, sizeof sizes);
  if (data_start + 8.0 > bytes.size() || sizes[1] != claimed_bytes || data_start + 8.0 + sizes[0] > bytes.size()) {
    throw std::invalid_argument(where +
                                "not a readable PCD file (damaged compressed data: sizes do not match the header)");
  }
}

// What the header's text says, read before PCL reads it: PCL 1.13 lets a later header line override an
// earlier one and then sizes the data by one while it lays the points out by the other (its ASCII
// reader writes past the cloud: found by fuzzing, seen by valgrind), and it allocates the points the
// header claims before it looks at the data. Lines are matched as PCL matches them: the first word
// (leading blanks skipped) by its prefix, COLUMNS for FIELDS, '#' for comments. PCL reads on past lines
// it does not know and past DATA (fuzzing showed both), so the whole file is scanned: a header line
// twice anywhere is refused (data lines are numbers or binary, which never spell a keyword in practice).
struct HeaderText {
  std::vector<std::string> fields;  ///< FIELDS.
  double points = 0;                ///< POINTS, else WIDTH x HEIGHT.
  double point_bytes = 0;           ///< The sum of SIZE x COUNT over the fields.
};

std::vector<std::string> Words(std::istringstream& line) {
  std::vector<std::string> words;
  for (std::string w; line >> w;) words.push_back(w);
  return words;
}

double Number(const std::vector<std::string>& words, size_t i) {
  return i < words.size() ? std::strtod(words[i].c_str(), nullptr) : 0.0;
}

// PCL drops a field with a COUNT below 1 and then reads freed memory for the others' names (valgrind):
// one SIZE (1, 2, 4 or 8), TYPE (I, U, F) and COUNT (a whole number >= 1) per field.
void CheckFieldLines(std::map<std::string, std::vector<std::string>>& lines, const std::string& where) {
  const size_t fields = lines["FIELDS"].size();
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(where + "not a readable PCD file (" + what + ")");
  };
  for (const char* key : {"SIZE", "TYPE", "COUNT"}) {
    if (lines.count(key) && lines[key].size() != fields) fail(std::string(key) + " does not give one value per field");
  }
  for (const std::string& size : lines["SIZE"]) {
    if (size != "1" && size != "2" && size != "4" && size != "8") fail("SIZE '" + size + "': expected 1, 2, 4 or 8");
  }
  for (const std::string& type : lines["TYPE"]) {
    if (type != "I" && type != "U" && type != "F") fail("TYPE '" + type + "': expected I, U or F");
  }
  for (const std::string& count : lines["COUNT"]) {
    if (count.empty() || count.size() > 7 || count.find_first_not_of("0123456789") != std::string::npos ||
        std::stoi(count) < 1) {
      fail("COUNT '" + count + "': expected a whole number of at least 1");
    }
  }
}

HeaderText ScanHeaderText(const std::string& bytes, const std::string& where) {
  static const std::vector<std::pair<std::string, std::string>> kPrefixes{
      {"VERSION", "VERSION"},     {"FIELDS", "FIELDS"}, {"COLUMNS", "FIELDS"}, {"SIZE", "SIZE"},
      {"TYPE", "TYPE"},           {"COUNT", "COUNT"},   {"WIDTH", "WIDTH"},    {"HEIGHT", "HEIGHT"},
      {"VIEWPOINT", "VIEWPOINT"}, {"POINTS", "POINTS"}, {"DATA", "DATA"}};
  std::istringstream in(bytes);
  std::map<std::string, std::vector<std::string>> values;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word[0] == '#') continue;
    const auto known = std::find_if(kPrefixes.begin(), kPrefixes.end(),
                                    [&](const auto& p) { return word.compare(0, p.first.size(), p.first) == 0; });
    if (known == kPrefixes.end()) continue;
    if (values.count(known->second)) {
      throw std::invalid_argument(where + "not a readable PCD file (header line '" + known->second + "' given twice)");
    }
    values[known->second] = Words(words);
  }
  CheckFieldLines(values, where);
  HeaderText h;
  h.fields = values["FIELDS"];
  h.points =
      values.count("POINTS") ? Number(values["POINTS"], 0) : Number(values["WIDTH"], 0) * Number(values["HEIGHT"], 0);
  // Without SIZE or COUNT lines PCL takes 4-byte fields of one value each.
  const std::vector<std::string>& sizes = values["SIZE"];
  const std::vector<std::string>& counts = values["COUNT"];
  for (size_t i = 0; i < h.fields.size(); ++i) {
    h.point_bytes += (i < sizes.size() ? Number(sizes, i) : 4.0) * (i < counts.size() ? Number(counts, i) : 1.0);
  }
  return h;
}

// The fields PCL made of the header lie one after the other and add up to a point.
void CheckFieldLayout(const pcl::PCLPointCloud2& blob, const std::string& where) {
  size_t point_bytes = 0;
  for (const pcl::PCLPointField& f : blob.fields) {
    const size_t size = pcl::getFieldSize(f.datatype);
    if (size == 0 || f.count == 0 || f.offset != point_bytes) {
      throw std::invalid_argument(where + "not a readable PCD file (field '" + f.name + "': bad SIZE, TYPE or COUNT)");
    }
    point_bytes += size * f.count;
  }
  if (point_bytes != blob.point_step) {
    throw std::invalid_argument(where + "not a readable PCD file (the fields do not add up to a point)");
  }
}

// PCL converts a field by its name whatever its type and size says: one that is not `size` bytes
// holding one value of an allowed type would be read past its end.
void CheckField(const pcl::PCLPointCloud2& blob, const std::string& name, std::initializer_list<uint8_t> types,
                const std::string& where) {
  for (const pcl::PCLPointField& f : blob.fields) {
    if (f.name != name) continue;
    const bool type_ok = std::find(types.begin(), types.end(), f.datatype) != types.end();
    if (!type_ok || f.count != 1 || f.offset + 4 > blob.point_step) {
      throw std::invalid_argument(where + "field '" + name + "': expected one 4-byte " +
                                  (name == "label" ? "unsigned integer"
                                   : name == "rgb" ? "packed colour"
                                                   : "float") +
                                  " per point");
    }
  }
}

// The whole file, read once: the header scan, the size checks and PCL's parsers all work on these
// bytes (PCL's own read opens the file twice more and maps it).
std::string ReadFileBytes(const std::filesystem::path& file, const std::string& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw std::invalid_argument(where + "no such file");
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  std::string bytes(size > 0 ? static_cast<size_t>(size) : 0, '\0');
  if (size < 0 || !in.seekg(0) || !in.read(bytes.data(), size))
    throw std::invalid_argument(where + "cannot read the file");
  return bytes;
}

struct PcdLayout {
  int version = 0;
  int data_type = 0;  ///< PCL's: 0 ascii, 1 binary, 2 binary_compressed.
  unsigned int data_start = 0;
};

// PCL's header parse, checked where PCL 1.13 does not check (it crashes instead): the fields it made
// must be the scanned ones, laid end to end, with x, y, z as floats.
PcdLayout ReadCheckedHeader(const std::string& bytes, const HeaderText& text, pcl::PCLPointCloud2& blob,
                            const std::string& where) {
  PcdLayout layout;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  std::istringstream in(bytes);
  int header = -1;
  try {
    header =
        pcl::PCDReader().readHeader(in, blob, origin, orientation, layout.version, layout.data_type, layout.data_start);
  } catch (const std::exception& e) {  // PCL 1.13 throws std::out_of_range for some malformed headers.
    throw std::invalid_argument(where + "not a readable PCD file (damaged header: " + e.what() + ")");
  }
  if (header < 0 || blob.fields.empty() || blob.width == 0 || blob.height == 0) {
    throw std::invalid_argument(where + "not a readable PCD file (no FIELDS or no points in the header)");
  }
  // PCL may read on past a DATA line it does not take for one; then what it read is not the header.
  bool same_fields = blob.fields.size() == text.fields.size();
  for (size_t i = 0; same_fields && i < blob.fields.size(); ++i) same_fields = blob.fields[i].name == text.fields[i];
  if (!same_fields) throw std::invalid_argument(where + "not a readable PCD file (damaged header: FIELDS after DATA)");
  CheckFieldLayout(blob, where);
  // PCL's binary reader reads x, y and z of every point as floats (to see whether the cloud is dense).
  for (const char* field : {"x", "y", "z"}) CheckField(blob, field, {pcl::PCLPointField::FLOAT32}, where);
  return layout;
}

// The points, through PCL's body parsers, from the bytes: the binary data must lie in the file (PCL
// checks that against the file's size, which it no longer sees).
void ReadBody(const std::string& bytes, const PcdLayout& layout, pcl::PCLPointCloud2& blob, const std::string& where) {
  const double claimed_bytes = static_cast<double>(blob.width) * blob.height * blob.point_step;
  // PCL takes the end of the stream (-1) for the data's start when DATA is the file's last line; its
  // ASCII parser would then wait forever on a stream that failed without reaching its end.
  if (layout.data_start >= bytes.size())
    throw std::invalid_argument(where + "not a readable PCD file (no data after DATA)");
  if (layout.data_type == 2) CheckCompressedSizes(bytes, layout.data_start, claimed_bytes, where);
  if (layout.data_type == 1 && layout.data_start + claimed_bytes > bytes.size()) {
    throw std::invalid_argument(where + "not a readable PCD file (the data is shorter than the header says)");
  }
  int read = -1;
  try {
    pcl::PCDReader reader;
    if (layout.data_type == 0) {
      std::istringstream in(bytes);
      in.seekg(layout.data_start);
      read = reader.readBodyASCII(in, blob, layout.version);
    } else {
      read = reader.readBodyBinary(reinterpret_cast<const unsigned char*>(bytes.data()), blob, layout.version,
                                   layout.data_type == 2, layout.data_start);
    }
  } catch (const std::exception& e) {
    throw std::invalid_argument(where + "not a readable PCD file (damaged: " + e.what() + ")");
  }
  if (read < 0) throw std::invalid_argument(where + "not a readable PCD file (damaged data)");
  if (blob.data.size() != claimed_bytes) {
    throw std::invalid_argument(where + "not a readable PCD file (the data does not match the header)");
  }
}

// The file's header and data, read once and checked where PCL 1.13 does not check.
pcl::PCLPointCloud2 ReadBlob(const std::filesystem::path& file, const std::string& where) {
  const std::string bytes = ReadFileBytes(file, where);
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // Errors are ours, one line each.
  // A header that claims more points than the file could hold (even compressed: LZF shrinks at most
  // ~100 times) is refused before PCL allocates them (its readHeader does, at the POINTS line).
  const HeaderText text = ScanHeaderText(bytes, where);
  if (text.points * text.point_bytes > 128.0 * bytes.size() + (1 << 20)) {
    throw std::invalid_argument(where + "not a readable PCD file (the header claims more points than the file holds)");
  }
  pcl::PCLPointCloud2 blob;
  const PcdLayout layout = ReadCheckedHeader(bytes, text, blob, where);
  ReadBody(bytes, layout, blob, where);
  return blob;
}

}  // namespace

std::vector<int> LoadMosdObjectIds(const std::filesystem::path& file) {
  const std::string where = "PCD '" + file.string() + "': ";
  pcl::PCLPointCloud2 blob = ReadBlob(file, where);
  if (!HasField(blob, "label")) throw std::invalid_argument(where + "no 'label' field");
  CheckField(blob, "label", {pcl::PCLPointField::UINT32, pcl::PCLPointField::INT32}, where);
  pcl::PointCloud<pcl::PointXYZL> labelled;
  pcl::fromPCLPointCloud2(blob, labelled);
  std::vector<int> ids(labelled.size(), 0);
  for (size_t i = 0; i < labelled.size(); ++i) {
    if (labelled[i].label >= 10) ids[i] = static_cast<int>(labelled[i].label / 10);
  }
  return ids;
}

Cloud::Ptr LoadCloud(const std::filesystem::path& file, bool organized) {
  const std::string where = "PCD '" + file.string() + "': ";
  pcl::PCLPointCloud2 blob = ReadBlob(file, where);
  for (const char* field : {"x", "y", "z"}) {
    if (!HasField(blob, field)) throw std::invalid_argument(where + "missing field '" + field + "'");
  }
  if (!HasField(blob, "rgb")) {
    auto rgba = std::find_if(blob.fields.begin(), blob.fields.end(), [](const auto& f) { return f.name == "rgba"; });
    if (rgba == blob.fields.end())
      throw std::invalid_argument(where + "missing field 'rgb' (or 'rgba'): colour is needed");
    rgba->name = "rgb";  // Same packing; PCL matches fields by name.
  }
  CheckField(blob, "rgb", {pcl::PCLPointField::FLOAT32, pcl::PCLPointField::UINT32, pcl::PCLPointField::INT32}, where);
  if (organized && blob.height <= 1) {
    throw std::invalid_argument(where + "not organized (" + std::to_string(blob.width) + "x" +
                                std::to_string(blob.height) + "): expected one point per pixel, e.g. 640x480");
  }
  auto cloud = std::make_shared<Cloud>();
  pcl::fromPCLPointCloud2(blob, *cloud);
  return cloud;
}

void SaveCloud(const std::filesystem::path& file, const Cloud& cloud) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  if (cloud.empty() || pcl::io::savePCDFileBinaryCompressed(file.string(), cloud) != 0) {
    throw std::runtime_error("cannot write '" + file.string() + "'");
  }
}

}  // namespace sortcell::perception
