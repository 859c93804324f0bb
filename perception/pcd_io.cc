#include "perception/pcd_io.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sortcell::perception {
namespace {

bool HasField(const pcl::PCLPointCloud2& blob, const std::string& name) {
  return std::any_of(blob.fields.begin(), blob.fields.end(), [&](const pcl::PCLPointField& f) { return f.name == name; });
}

}  // namespace

std::vector<int> LoadMosdObjectIds(const std::filesystem::path& file) {
  pcl::PCLPointCloud2 blob;
  if (pcl::io::loadPCDFile(file.string(), blob) != 0) {
    throw std::invalid_argument("PCD '" + file.string() + "': not a readable PCD file");
  }
  if (!HasField(blob, "label")) throw std::invalid_argument("PCD '" + file.string() + "': no 'label' field");
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
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw std::invalid_argument(where + "no such file");
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // Errors are ours, one line each.
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  // PCL 1.13's read() crashes on a file without a PCD header: check the header first.
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, binary = 0;
  unsigned int data_start = 0;
  if (reader.readHeader(file.string(), blob, origin, orientation, version, binary, data_start) < 0 ||
      blob.fields.empty() || blob.width == 0 || blob.height == 0) {
    throw std::invalid_argument(where + "not a readable PCD file (no FIELDS or no points in the header)");
  }
  if (reader.read(file.string(), blob) < 0) throw std::invalid_argument(where + "not a readable PCD file (damaged data)");
  for (const char* field : {"x", "y", "z"}) {
    if (!HasField(blob, field)) throw std::invalid_argument(where + "missing field '" + field + "'");
  }
  if (!HasField(blob, "rgb")) {
    auto rgba = std::find_if(blob.fields.begin(), blob.fields.end(), [](const auto& f) { return f.name == "rgba"; });
    if (rgba == blob.fields.end()) throw std::invalid_argument(where + "missing field 'rgb' (or 'rgba'): colour is needed");
    rgba->name = "rgb";  // Same packing; PCL matches fields by name.
  }
  if (blob.width == 0 || blob.height == 0) throw std::invalid_argument(where + "the cloud is empty");
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
