// Fuzz target: an image file (assets::ReadImage: lodepng for PNG, libjpeg-turbo for JPEG), as a
// texture, a colour crop, a mask and a depth map are read. It never throws: a file that does not
// decode reads as an empty image, which each caller refuses naming the file.
#include "assets/image_file.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "input.img";
  sortcell_fuzz::WriteInput(file, data, size);
  using sortcell::assets::PixelFormat;
  for (const PixelFormat format : {PixelFormat::kBgr8, PixelFormat::kGrey8, PixelFormat::kGrey16}) {
    const cv::Mat image = sortcell::assets::ReadImage(file, format);
    if (!image.empty() && image.channels() != (format == PixelFormat::kBgr8 ? 3 : 1)) std::abort();
  }
  return 0;
}
