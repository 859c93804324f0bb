// Measures the Kinect v1 colour camera: real views in the RGB-D Object Dataset's format against a clean
// render of the produce set by the simulated Kinect, and prints the colour model (sim/kinect_colour.h)
// they imply. Figures, not a test.
// Usage: kinect_colour_measure [RGBD_DIR]   (default: ../shared/real/rgbd-object beside the checkout)
//
// What is compared, and why:
//  - a white surface (exposure, white balance): the real turntable's top (bright, unsaturated pixels
//    outside the object's mask) against the rendered plates (white glaze);
//  - a yellow object (saturation): the real banana's masked pixels against the rendered lemons;
//  - blur: how much of the gradient a further 1 px blur takes away over the object and its edge (real
//    views), and the blur that gives the render the same;
//  - noise: the robust spread of what a 3x3 median takes away inside the object (real against rendered).
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_args.h"
#include "files/data_dir.h"
#include "training/rgbd_objects.h"
#include "assets/image_file.h"
#include "sim/kinect_camera.h"
#include "sim/model.h"

namespace {

namespace fs = std::filesystem;

struct Stats {
  double n = 0;
  cv::Vec3d rgb{0, 0, 0};
  double s = 0, v = 0;
  void Add(const cv::Vec3b& rgb_pixel, const cv::Vec3b& hsv_pixel) {
    rgb += cv::Vec3d(rgb_pixel[0], rgb_pixel[1], rgb_pixel[2]);
    s += hsv_pixel[1];
    v += hsv_pixel[2];
    ++n;
  }
  cv::Vec3d Rgb() const { return rgb / std::max(1.0, n); }
  double S() const { return s / std::max(1.0, n); }
  double V() const { return v / std::max(1.0, n); }
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Sharpness: the mean gradient magnitude of the grey image over the object and 3 px around it, over
// that of the same image blurred with sigma 1 px. A sharp image loses much to the blur (a high ratio),
// an already soft one little.
double SharpnessRatio(const cv::Mat& rgb, const cv::Mat& mask) {
  cv::Mat grey, region, soft;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::dilate(mask, region, cv::Mat(), cv::Point(-1, -1), 3);
  cv::GaussianBlur(grey, soft, cv::Size(0, 0), 1.0);
  const auto gradient = [&region](const cv::Mat& image) {
    cv::Mat gx, gy, magnitude;
    cv::Sobel(image, gx, CV_32F, 1, 0);
    cv::Sobel(image, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    return cv::mean(magnitude, region)[0];
  };
  return gradient(grey) / std::max(1e-9, gradient(soft));
}

// The blur sigma that, applied to the render, gives it the real views' sharpness ratio.
double MatchingBlur(const cv::Mat& rgb, const cv::Mat& mask, double target_ratio) {
  double best = 0, best_gap = 1e9;
  for (double sigma = 0; sigma <= 3.001; sigma += 0.1) {
    cv::Mat blurred = rgb;
    if (sigma > 0) cv::GaussianBlur(rgb, blurred, cv::Size(0, 0), sigma);
    const double gap = std::abs(SharpnessRatio(blurred, mask) - target_ratio);
    if (gap < best_gap) best_gap = gap, best = sigma;
  }
  return best;
}

// Per-pixel noise (8-bit levels) inside the object: the mean absolute residual of a 3x3 median over the
// green channel (the Bayer pattern's densest), as a Gaussian's sigma (x 1.25).
double InteriorNoise(const cv::Mat& rgb, const cv::Mat& mask) {
  cv::Mat inner, green, smooth;
  cv::erode(mask, inner, cv::Mat(), cv::Point(-1, -1), 3);
  cv::extractChannel(rgb, green, 1);
  cv::medianBlur(green, smooth, 3);
  std::vector<double> residuals;
  for (int y = 0; y < rgb.rows; ++y) {
    for (int x = 0; x < rgb.cols; ++x) {
      if (inner.at<uint8_t>(y, x)) residuals.push_back(std::abs(green.at<uint8_t>(y, x) - smooth.at<uint8_t>(y, x)));
    }
  }
  double sum = 0;
  for (double r : residuals) sum += r;
  return residuals.empty() ? 0.0 : 1.25 * sum / residuals.size();
}

struct Measured {
  Stats object, white;
  std::vector<double> sharpness, noises;
  cv::Mat image, mask;  // Render only: the image and the objects' mask, to match the blur on.
};

cv::Mat Hsv(const cv::Mat& rgb) {
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  return hsv;
}

void AddWhite(const cv::Mat& rgb, const cv::Mat& not_object, Stats& white) {
  // The brightest third of the unsaturated pixels that are not the object: the white surface.
  const cv::Mat hsv = Hsv(rgb);
  std::vector<double> values;
  for (int y = 0; y < rgb.rows; ++y)
    for (int x = 0; x < rgb.cols; ++x)
      if (not_object.at<uint8_t>(y, x) && hsv.at<cv::Vec3b>(y, x)[1] < 40) values.push_back(hsv.at<cv::Vec3b>(y, x)[2]);
  if (values.size() < 50) return;
  std::sort(values.begin(), values.end());
  const double threshold = values[values.size() * 2 / 3];
  for (int y = 0; y < rgb.rows; ++y)
    for (int x = 0; x < rgb.cols; ++x)
      if (not_object.at<uint8_t>(y, x) && hsv.at<cv::Vec3b>(y, x)[1] < 40 && hsv.at<cv::Vec3b>(y, x)[2] >= threshold)
        white.Add(rgb.at<cv::Vec3b>(y, x), hsv.at<cv::Vec3b>(y, x));
}

void AddObject(const cv::Mat& rgb, const cv::Mat& mask, Measured& m) {
  cv::Mat inner;
  cv::erode(mask, inner, cv::Mat(), cv::Point(-1, -1), 2);
  const cv::Mat hsv = Hsv(rgb);
  for (int y = 0; y < rgb.rows; ++y)
    for (int x = 0; x < rgb.cols; ++x)
      if (inner.at<uint8_t>(y, x)) m.object.Add(rgb.at<cv::Vec3b>(y, x), hsv.at<cv::Vec3b>(y, x));
  m.sharpness.push_back(SharpnessRatio(rgb, mask));
  m.noises.push_back(InteriorNoise(rgb, mask));
}

Measured MeasureReal(const fs::path& dir) {
  Measured m;
  for (const auto& view : sortcell::training::FindRgbdObjectsViews(dir)) {
    cv::Mat bgr = sortcell::assets::ReadImage(view.crop, sortcell::assets::PixelFormat::kBgr8);
    cv::Mat mask = sortcell::assets::ReadImage(sortcell::training::Partner(view, "maskcrop.png"),
                                               sortcell::assets::PixelFormat::kGrey8);
    cv::Mat depth = sortcell::assets::ReadImage(sortcell::training::Partner(view, "depthcrop.png"),
                                                sortcell::assets::PixelFormat::kGrey16);
    if (bgr.empty() || mask.empty() || depth.empty() || mask.size() != bgr.size()) continue;
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    mask = mask > 0;
    AddObject(rgb, mask & (depth > 0), m);
    cv::Mat around;
    cv::dilate(mask, around, cv::Mat(), cv::Point(-1, -1), 3);
    AddWhite(rgb, ~around & (depth > 0), m.white);
  }
  return m;
}

// The produce set on the table, seen by the simulated Kinect without noise: the lemons (yellow) as the
// object, the plates (white) as the white surface.
Measured MeasureRender() {
  using namespace sortcell;
  const sim::Model model = files::LoadScene(fs::path(files::DataDir()) / "scenes" / "produce.xml");
  sim::Data data(model);
  sim::ResetToObserve(model, data);
  sim::Step(model, data, 1);
  sim::KinectCamera kinect(model, "kinect");
  sim::FrameTruth truth;
  const sim::KinectFrame frame = kinect.Capture(data, nullptr, nullptr, &truth);
  Measured m;
  cv::Mat plates = cv::Mat::zeros(frame.rgb.size(), CV_8UC1);
  for (size_t i = 0; i < kinect.object_names().size(); ++i) {
    const std::string& name = kinect.object_names()[i];
    const cv::Mat mask = truth.labels == static_cast<uint16_t>(i + 1);
    if (cv::countNonZero(mask) < 100) continue;
    if (name.rfind("lemon", 0) == 0) {
      AddObject(frame.rgb, mask, m);
      m.mask = m.mask.empty() ? mask.clone() : (m.mask | mask);
    }
    if (name.rfind("plate", 0) == 0) plates |= mask;
  }
  cv::erode(plates, plates, cv::Mat(), cv::Point(-1, -1), 2);
  AddWhite(frame.rgb, plates, m.white);
  m.image = frame.rgb;
  return m;
}

void Print(const char* what, const Measured& m) {
  const cv::Vec3d w = m.white.Rgb(), o = m.object.Rgb();
  std::printf(
      "%-22s white RGB (%5.1f %5.1f %5.1f) V %5.1f [%6.0f px] | object RGB (%5.1f %5.1f %5.1f) S %5.1f V %5.1f "
      "[%6.0f px] | sharpness %.2f | noise %.2f levels\n",
      what, w[0], w[1], w[2], m.white.V(), m.white.n, o[0], o[1], o[2], m.object.S(), m.object.V(), m.object.n,
      Median(m.sharpness), Median(m.noises));
}

int Run(int argc, char** argv) {
  fs::path real_dir = fs::path(SORTCELL_SOURCE_DIR) / ".." / "shared" / "real" / "rgbd-object";
  CLI::App cli("Compares the Kinect colour model's renders with real RGB-D Object Dataset views.",
               "kinect_colour_measure");
  cli.add_option("folder", real_dir, "a folder of RGB-D Object Dataset views (default: ../shared/real/rgbd-object)");
  if (const auto exit_code = ParseBenchmarkArgs(cli, argc, argv)) return *exit_code;
  // Checked here, not by CLI11: the default folder is not a value CLI11 sees.
  if (!fs::is_directory(real_dir)) {
    throw std::invalid_argument("'" + real_dir.string() + "' is not a folder of RGB-D Object Dataset views");
  }
  const Measured real = MeasureReal(real_dir);
  const Measured render = MeasureRender();
  if (real.object.n == 0 || render.object.n == 0 || render.white.n == 0 || real.white.n == 0) {
    std::fprintf(stderr, "kinect_colour_measure: no object or white pixels found\n");
    return 2;
  }
  std::printf("real: %s (%zu views; object = masked pixels with depth; white = the turntable)\n", real_dir.c_str(),
              real.sharpness.size());
  Print("real Kinect", real);
  Print("render (lemons, plates)", render);
  const cv::Vec3d wr = real.white.Rgb(), ws = render.white.Rgb();
  const double exposure = real.white.V() / render.white.V();
  const double mean_r = (wr[0] + wr[1] + wr[2]) / 3, mean_s = (ws[0] + ws[1] + ws[2]) / 3;
  cv::Vec3d balance((wr[0] / mean_r) / (ws[0] / mean_s), (wr[1] / mean_r) / (ws[1] / mean_s),
                    (wr[2] / mean_r) / (ws[2] / mean_s));
  balance /= (balance[0] + balance[1] + balance[2]) / 3;
  const double saturation = real.object.S() / render.object.S();
  const double blur = MatchingBlur(render.image, render.mask, Median(real.sharpness));
  const double nr = Median(real.noises), ns = Median(render.noises);
  const double noise = std::sqrt(std::max(0.0, nr * nr - ns * ns));
  std::printf(
      "implied colour model: exposure %.2f, white balance (%.2f %.2f %.2f), saturation %.2f, blur sigma %.2f px, "
      "noise %.2f levels\n",
      exposure, balance[0], balance[1], balance[2], saturation, blur, noise);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return RunBenchmark("kinect_colour_measure", [&] { return Run(argc, argv); });
}
