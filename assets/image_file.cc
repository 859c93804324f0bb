#include "assets/image_file.h"

#include <lodepng.h>
#include <turbojpeg.h>

#include <opencv2/imgproc.hpp>

#include <vector>

namespace sortcell::assets {
namespace {

// Larger images are refused as OpenCV's imread refuses them (CV_IO_MAX_IMAGE_PIXELS): a file of a few
// bytes can declare a size that would take gigabytes. 8192 x 8192 is more than any texture or crop.
constexpr double kMaxPixels = 8192.0 * 8192.0;

bool IsJpeg(const std::vector<unsigned char>& bytes) {
  return bytes.size() > 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

cv::Mat DecodeJpeg(const std::vector<unsigned char>& bytes, PixelFormat format) {
  if (format == PixelFormat::kGrey16) return {};
  tjhandle decoder = tjInitDecompress();
  if (decoder == nullptr) return {};
  int width = 0, height = 0, subsampling = 0, colourspace = 0;
  cv::Mat image;
  // A warning (extra bytes before a marker, a truncated scan) still gives an image, as imread's does.
  const auto ok = [&](int status) { return status == 0 || tjGetErrorCode(decoder) == TJERR_WARNING; };
  if (ok(tjDecompressHeader3(decoder, bytes.data(), bytes.size(), &width, &height, &subsampling, &colourspace)) &&
      width > 0 && height > 0 && static_cast<double>(width) * height <= kMaxPixels) {
    const bool grey = format == PixelFormat::kGrey8;
    image.create(height, width, grey ? CV_8UC1 : CV_8UC3);
    // Flags 0: the accurate integer DCT and smooth chroma upsampling, as OpenCV's imread decodes.
    if (!ok(tjDecompress2(decoder, bytes.data(), bytes.size(), image.data, width, static_cast<int>(image.step), height,
                          grey ? TJPF_GRAY : TJPF_BGR, 0))) {
      image.release();
    }
  }
  tjDestroy(decoder);
  return image;
}

cv::Mat DecodePng(const std::vector<unsigned char>& bytes, PixelFormat format) {
  unsigned width = 0, height = 0;
  lodepng::State state;
  if (lodepng_inspect(&width, &height, &state, bytes.data(), bytes.size()) != 0) return {};
  if (static_cast<double>(width) * height > kMaxPixels) return {};
  const LodePNGColorMode& stored = state.info_png.color;
  const bool grey_file = stored.colortype == LCT_GREY || stored.colortype == LCT_GREY_ALPHA;
  if (format == PixelFormat::kGrey16 && !(grey_file && stored.bitdepth == 16)) return {};
  const bool sixteen = format == PixelFormat::kGrey16;
  // lodepng converts grey to RGB but not RGB to grey: a colour file asked for in grey goes through RGB.
  const LodePNGColorType decode_as = format != PixelFormat::kBgr8 && grey_file ? LCT_GREY : LCT_RGB;
  std::vector<unsigned char> pixels;
  if (lodepng::decode(pixels, width, height, bytes, decode_as, sixteen ? 16 : 8) != 0) return {};
  if (sixteen) {
    cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_16UC1);
    auto* out = image.ptr<uint16_t>();
    for (size_t i = 0; i < image.total(); ++i) out[i] = static_cast<uint16_t>(pixels[2 * i] << 8 | pixels[2 * i + 1]);
    return image;
  }
  const cv::Mat decoded(static_cast<int>(height), static_cast<int>(width), decode_as == LCT_GREY ? CV_8UC1 : CV_8UC3,
                        pixels.data());
  cv::Mat image;
  if (decode_as == LCT_GREY) return decoded.clone();
  cv::cvtColor(decoded, image, format == PixelFormat::kGrey8 ? cv::COLOR_RGB2GRAY : cv::COLOR_RGB2BGR);
  return image;
}

}  // namespace

cv::Mat ReadImage(const std::filesystem::path& file, PixelFormat format) {
  std::vector<unsigned char> bytes;
  if (lodepng::load_file(bytes, file.string()) != 0 || bytes.empty()) return {};
  return IsJpeg(bytes) ? DecodeJpeg(bytes, format) : DecodePng(bytes, format);
}

bool WritePng(const std::filesystem::path& file, const cv::Mat& image) {
  if (image.empty()) return false;
  std::vector<unsigned char> pixels;
  LodePNGColorType type = LCT_RGB;
  unsigned depth = 8;
  if (image.type() == CV_8UC3) {
    cv::Mat rgb;
    cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
    pixels.assign(rgb.data, rgb.data + rgb.total() * 3);
  } else if (image.type() == CV_8UC1) {
    type = LCT_GREY;
    const cv::Mat grey = image.isContinuous() ? image : image.clone();
    pixels.assign(grey.data, grey.data + grey.total());
  } else if (image.type() == CV_16UC1) {
    type = LCT_GREY;
    depth = 16;
    pixels.reserve(image.total() * 2);
    for (int r = 0; r < image.rows; ++r) {
      for (int c = 0; c < image.cols; ++c) {
        const uint16_t v = image.at<uint16_t>(r, c);
        pixels.push_back(static_cast<unsigned char>(v >> 8));  // PNG holds 16-bit samples big-endian.
        pixels.push_back(static_cast<unsigned char>(v & 0xFF));
      }
    }
  } else {
    return false;
  }
  // As given: lodepng would otherwise store the smallest type that holds the pixels (an all-zero 16-bit
  // depth map as a 1-bit image).
  lodepng::State state;
  state.encoder.auto_convert = 0;
  state.info_raw.colortype = state.info_png.color.colortype = type;
  state.info_raw.bitdepth = state.info_png.color.bitdepth = depth;
  std::vector<unsigned char> png;
  if (lodepng::encode(png, pixels, static_cast<unsigned>(image.cols), static_cast<unsigned>(image.rows), state) != 0) {
    return false;
  }
  return lodepng::save_file(png, file.string()) == 0;
}

}  // namespace sortcell::assets
