#pragma once
/// @file
/// Image files: PNG (lodepng, which MuJoCo also uses) and JPEG (libjpeg-turbo's TurboJPEG, the decoder
/// OpenCV's imread uses) to and from cv::Mat. Why not OpenCV's imgcodecs: it links GDAL and with it
/// some 100 shared libraries, and the dynamic loader's symbol lookups made every start of `sortcell`
/// (each test, each sweep worker) about 0.15 s slower for reading a texture or writing a still.
#include <filesystem>

#include <opencv2/core/mat.hpp>

namespace sortcell::assets {

enum class PixelFormat {
  kBgr8,    ///< CV_8UC3 in OpenCV's channel order (a grey file is spread to three channels).
  kGrey8,   ///< CV_8UC1 (a colour file is converted to grey).
  kGrey16,  ///< CV_16UC1, from a 16-bit grey PNG only (depth in millimetres).
};

/// A PNG or JPEG file (told apart by its content) in `format`; empty when the file is missing, does not
/// decode, or holds no 16-bit grey PNG where kGrey16 is asked.
cv::Mat ReadImage(const std::filesystem::path& file, PixelFormat format);

/// Writes an 8-bit BGR, an 8-bit grey or a 16-bit grey image as a PNG; false when it cannot (another
/// type of image, a folder that does not exist).
bool WritePng(const std::filesystem::path& file, const cv::Mat& image);

}  // namespace sortcell::assets
