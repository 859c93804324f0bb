#include "perception/pcd_io.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

namespace sortcell::perception {
namespace {

bool HasField(const pcl::PCLPointCloud2& blob, const std::string& name) {
  return std::any_of(blob.fields.begin(), blob.fields.end(), [&](const pcl::PCLPointField& f) { return f.name == name; });
}

// DATA binary_compressed starts with the compressed and the uncompressed sizes, which PCL allocates
// before it checks them: the uncompressed must be what the header's points take, the compressed must
// be in the file.
void CheckCompressedSizes(const std::filesystem::path& file, unsigned int data_start, double claimed_bytes,
                          const std::string& where) {
  std::ifstream in(file, std::ios::binary);
  uint32_t sizes[2] = {0, 0};
  in.seekg(data_start);
  in.read(reinterpret_cast<char*>(sizes), sizeof sizes);
  std::error_code ec;
  const double file_bytes = static_cast<double>(std::filesystem::file_size(file, ec));
  if (!in || ec || sizes[1] != claimed_bytes || data_start + 8.0 + sizes[0] > file_bytes) {
    throw std::invalid_argument(where + "not a readable PCD file (damaged compressed data: sizes do not match the header)");
  }
}

// The file's header and data, checked where PCL 1.13 does not check (it crashes instead): a file
// without a header, data shorter than the header says.
pcl::PCLPointCloud2 ReadBlob(const std::filesystem::path& file, const std::string& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw std::invalid_argument(where + "no such file");
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // Errors are ours, one line each.
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, binary = 0;
  unsigned int data_start = 0;
  int header = -1;
  try {
    header = reader.readHeader(file.string(), blob, origin, orientation, version, binary, data_start);
  } catch (const std::exception& e) {  // PCL 1.13 throws std::out_of_range for some malformed headers.
    throw std::invalid_argument(where + "not a readable PCD file (damaged header: " + e.what() + ")");
  }
  if (header < 0 || blob.fields.empty() || blob.width == 0 || blob.height == 0) {
    throw std::invalid_argument(where + "not a readable PCD file (no FIELDS or no points in the header)");
  }
  // PCL allocates what the header claims before it reads: a header that claims more points than the
  // file could hold (even compressed: LZF shrinks at most ~100 times) is refused before that.
  const double claimed_bytes = static_cast<double>(blob.width) * blob.height * blob.point_step;
  const double file_bytes = static_cast<double>(std::filesystem::file_size(file, ec));
  if (ec || claimed_bytes > 128 * file_bytes + (1 << 20)) {
    throw std::invalid_argument(where + "not a readable PCD file (the header claims " + std::to_string(blob.width) + "x" +
                                std::to_string(blob.height) + " points, more than the file holds)");
  }
  if (binary == 2) CheckCompressedSizes(file, data_start, claimed_bytes, where);
  int read = -1;
  try {
    read = reader.read(file.string(), blob);
  } catch (const std::exception& e) {
    throw std::invalid_argument(where + "not a readable PCD file (damaged: " + e.what() + ")");
  }
  if (read < 0) throw std::invalid_argument(where + "not a readable PCD file (damaged data)");
  if (blob.data.size() != static_cast<size_t>(blob.width) * blob.height * blob.point_step) {
    throw std::invalid_argument(where + "not a readable PCD file (the data does not match the header)");
  }
  return blob;
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
                                  (name == "label" ? "unsigned integer" : name == "rgb" ? "packed colour" : "float") +
                                  " per point");
    }
  }
}

}  // namespace

std::vector<int> LoadMosdObjectIds(const std::filesystem::path& file) {
  const std::string where = "PCD '" + file.string() + "': ";
  pcl::PCLPointCloud2 blob = ReadBlob(file, where);
  if (!HasField(blob, "label")) throw std::invalid_argument(where + "no 'label' field");
  CheckField(blob, "label", {pcl::PCLPointField::UINT32, pcl::PCLPointField::INT32}, where);
  for (const char* field : {"x", "y", "z"}) CheckField(blob, field, {pcl::PCLPointField::FLOAT32}, where);
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
    CheckField(blob, field, {pcl::PCLPointField::FLOAT32}, where);
  }
  if (!HasField(blob, "rgb")) {
    auto rgba = std::find_if(blob.fields.begin(), blob.fields.end(), [](const auto& f) { return f.name == "rgba"; });
    if (rgba == blob.fields.end()) throw std::invalid_argument(where + "missing field 'rgb' (or 'rgba'): colour is needed");
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
