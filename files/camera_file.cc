#include "files/camera_file.h"

#include <fstream>
#include <stdexcept>

namespace sortcell::files {

nlohmann::json CameraJson(const std::string& camera, const sim::KinectFrame& frame, const Eigen::Isometry3d& X_WC) {
  const auto& k = frame.intrinsics;
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < 4; ++c) row.push_back(X_WC.matrix()(r, c));
    rows.push_back(row);
  }
  return {
      {"camera", camera}, {"fx", k.fx},       {"fy", k.fy},         {"cx", k.cx},
      {"cy", k.cy},       {"width", k.width}, {"height", k.height}, {"frame", "optical: x right, y down, z forward"},
      {"X_WC", rows}};
}

Eigen::Isometry3d LoadCameraPose(const std::filesystem::path& file) {
  const std::string where = "camera file '" + file.string() + "': ";
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(where + "cannot be read");
  nlohmann::json json;
  try {
    in >> json;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(where + "not valid JSON (" + e.what() + ")");
  }
  if (!json.is_object() || !json.contains("X_WC")) throw std::invalid_argument(where + "missing key 'X_WC'");
  const nlohmann::json& rows = json["X_WC"];
  Eigen::Matrix4d m;
  if (!rows.is_array() || rows.size() != 4) throw std::invalid_argument(where + "'X_WC' must be 4 rows of 4 numbers");
  for (int r = 0; r < 4; ++r) {
    if (!rows[r].is_array() || rows[r].size() != 4) {
      throw std::invalid_argument(where + "'X_WC' must be 4 rows of 4 numbers");
    }
    for (int c = 0; c < 4; ++c) {
      if (!rows[r][c].is_number()) throw std::invalid_argument(where + "'X_WC' must be 4 rows of 4 numbers");
      m(r, c) = rows[r][c].get<double>();
    }
  }
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if (!m.allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-6 || R.determinant() < 0 ||
      (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9) {
    throw std::invalid_argument(where + "'X_WC' is not a rigid transform (rotation and last row 0 0 0 1)");
  }
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.matrix() = m;
  return X_WC;
}

}  // namespace sortcell::files
