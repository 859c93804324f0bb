#include "sim/kinect_colour.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <utility>
#include <stdexcept>
#include <string>

namespace sortcell::sim {
namespace {

void Check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Kinect colour model: " + what);
}

}  // namespace

std::string ToString(const KinectColourParams& p) {
  if (!p.enabled) return "off";
  char text[200];
  std::snprintf(text, sizeof text, "exposure %g, white balance %g %g %g, saturation %g, blur %g px, noise %g",
                p.exposure, p.white_balance_r, p.white_balance_g, p.white_balance_b, p.saturation, p.blur_sigma_px,
                p.noise_sigma);
  return text;
}

KinectColourParams JitterColour(const KinectColourParams& params, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> exposure(0.6, 1.2), saturation(0.85, 1.15), balance(0.96, 1.04);
  KinectColourParams p = params;
  p.exposure *= exposure(rng);
  p.saturation *= saturation(rng);
  p.white_balance_r *= balance(rng);
  p.white_balance_g *= balance(rng);
  p.white_balance_b *= balance(rng);
  return p;
}

cv::Mat ApplyKinectColour(const cv::Mat& rgb, const KinectColourParams& p, std::mt19937_64& rng) {
  Check(rgb.type() == CV_8UC3, "expected an 8-bit RGB image");
  const std::pair<const char*, double> fields[] = {{"exposure", p.exposure},
                                                   {"white_balance_r", p.white_balance_r},
                                                   {"white_balance_g", p.white_balance_g},
                                                   {"white_balance_b", p.white_balance_b},
                                                   {"saturation", p.saturation},
                                                   {"blur_sigma_px", p.blur_sigma_px},
                                                   {"noise_sigma", p.noise_sigma}};
  for (const auto& [name, value] : fields) {
    Check(value >= 0 && std::isfinite(value),
          std::string(name) + " must be finite and >= 0, got " + std::to_string(value));
  }
  if (!p.enabled) return rgb.clone();
  // Gains, then saturation about the luma (Rec. 601 weights), as one 3x3 map: out = S * G * in.
  const cv::Matx33d gains(p.exposure * p.white_balance_r, 0, 0, 0, p.exposure * p.white_balance_g, 0, 0, 0,
                          p.exposure * p.white_balance_b);
  const cv::Matx13d luma(0.299, 0.587, 0.114);
  const cv::Matx33d to_grey(luma(0), luma(1), luma(2), luma(0), luma(1), luma(2), luma(0), luma(1), luma(2));
  const cv::Matx33d saturate = p.saturation * cv::Matx33d::eye() + (1 - p.saturation) * to_grey;
  cv::Mat out;
  rgb.convertTo(out, CV_32FC3);
  cv::transform(out, out, cv::Matx33f(saturate * gains));
  if (p.blur_sigma_px > 0) cv::GaussianBlur(out, out, cv::Size(0, 0), p.blur_sigma_px);
  if (p.noise_sigma > 0) {
    cv::Mat noise(out.size(), CV_32FC3);
    cv::RNG noise_rng(rng());  // One seed from the capture's generator: deterministic, fast.
    noise_rng.fill(noise, cv::RNG::NORMAL, 0.0, p.noise_sigma);
    out += noise;
  }
  cv::Mat result;
  out.convertTo(result, CV_8UC3);  // Rounds and saturates to 0..255.
  return result;
}

}  // namespace sortcell::sim
