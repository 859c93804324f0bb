// Writes the calibration plate's faces (models/gripper/textures/calibration_plate_*.png): the ArUco
// marker robot::kMarkerId of OpenCV's 4x4_50 dictionary, robot::kMarkerSide wide, on a white plate
// with a 7 mm quiet zone (the face MuJoCo's cube texture calls "right", +x), plain white elsewhere.
//   ./build/make_calibration_marker models/gripper/textures
#include <opencv2/aruco.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "robot/gripper_geometry.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_calibration_marker DIR\n");
    return 2;
  }
  constexpr double kPxPerM = 6000;
  constexpr double kQuietZone = 0.007;  // White around the black square (m): the detector needs it.
  const int marker_px = static_cast<int>(std::lround(sortcell::robot::kMarkerSide * kPxPerM));
  const int margin_px = static_cast<int>(std::lround(kQuietZone * kPxPerM));
  const int face_px = marker_px + 2 * margin_px;
  cv::Mat marker;
  cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), sortcell::robot::kMarkerId,
                        marker_px, marker, 1);
  cv::Mat face(face_px, face_px, CV_8UC1, cv::Scalar(255));
  marker.copyTo(face(cv::Rect(margin_px, margin_px, marker_px, marker_px)));
  const cv::Mat white(face_px, face_px, CV_8UC1, cv::Scalar(255));
  const std::string dir = argv[1];
  bool ok = cv::imwrite(dir + "/calibration_plate_marker.png", face);
  ok = ok && cv::imwrite(dir + "/calibration_plate_blank.png", white);
  if (!ok) {
    std::fprintf(stderr, "make_calibration_marker: cannot write into '%s'\n", dir.c_str());
    return 2;
  }
  return 0;
}
