#include "training/rgbd_objects.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "files/output_dir.h"
#include "files/progress.h"
#include "assets/image_file.h"
#include "perception/pcd_io.h"

namespace sortcell::training {
namespace {

constexpr int kFrameWidth = 640, kFrameHeight = 480;
// The dataset's three camera heights, lowest first.
constexpr double kElevationsDeg[] = {30, 45, 60};

[[noreturn]] void Refuse(const std::filesystem::path& file, const std::string& what) {
  throw std::invalid_argument("'" + file.string() + "': " + what);
}

cv::Mat ReadImage(const std::filesystem::path& file, assets::PixelFormat format, int type, const char* expected) {
  if (!std::filesystem::is_regular_file(file)) Refuse(file, "missing");
  const cv::Mat image = assets::ReadImage(file, format);
  // An 8-bit file where 16-bit depth is asked for reads as empty: say which it is.
  if (image.empty() && format == assets::PixelFormat::kGrey16 &&
      !assets::ReadImage(file, assets::PixelFormat::kGrey8).empty()) {
    Refuse(file, std::string("expected ") + expected);
  }
  if (image.empty()) Refuse(file, "not a readable image");
  if (image.type() != type) Refuse(file, std::string("expected ") + expected);
  return image;
}

// The crop's top-left pixel in the frame, 0-based, from "X,Y" (1-based).
cv::Point ReadLoc(const std::filesystem::path& file, const cv::Size& crop) {
  std::ifstream in(file);
  if (!in) Refuse(file, "missing or unreadable");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream parse(text);
  int x = 0, y = 0;
  char comma = 0;
  std::string rest;
  if (!(parse >> x >> comma >> y) || comma != ',' || (parse >> rest)) Refuse(file, "expected \"X,Y\" (1-based pixel)");
  if (x < 1 || y < 1 || x - 1 + crop.width > kFrameWidth || y - 1 + crop.height > kFrameHeight) {
    Refuse(file, fmt::format("a {}x{} crop at ({}, {}) does not fit the {}x{} frame", crop.width, crop.height, x, y,
                             kFrameWidth, kFrameHeight));
  }
  return {x - 1, y - 1};
}

std::string CategoryOf(const std::filesystem::path& crop, const std::string& instance) {
  const std::filesystem::path folder = crop.parent_path();
  if (folder.filename() == instance && !folder.parent_path().filename().empty()) {
    return folder.parent_path().filename().string();
  }
  return std::regex_replace(instance, std::regex("_[0-9]+$"), "");
}

// Each instance's videos, lowest number first, as elevations.
std::map<std::pair<std::string, int>, double> Elevations(const std::vector<RgbdObjectsView>& views) {
  std::map<std::string, std::set<int>> videos;
  for (const auto& v : views) videos[v.instance].insert(v.video);
  std::map<std::pair<std::string, int>, double> elevation;
  for (const auto& [instance, numbers] : videos) {
    int rank = 0;
    for (int video : numbers) elevation[{instance, video}] = kElevationsDeg[std::min(rank++, 2)];
  }
  return elevation;
}

}  // namespace

std::filesystem::path Partner(const RgbdObjectsView& view, const std::string& suffix) {
  const std::string name = view.crop.filename().string();
  return view.crop.parent_path() / (name.substr(0, name.size() - std::string("crop.png").size()) + suffix);
}

std::vector<RgbdObjectsView> FindRgbdObjectsViews(const std::filesystem::path& root) {
  if (!std::filesystem::is_directory(root)) {
    throw std::invalid_argument("RGB-D Object Dataset folder '" + root.string() + "': not a folder");
  }
  static const std::regex kCrop("^(.+)_([0-9]+)_([0-9]+)_crop\\.png$");
  std::vector<RgbdObjectsView> views;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || !std::regex_match(name, m, kCrop)) continue;
    RgbdObjectsView view;
    view.crop = entry.path();
    view.instance = m[1];
    view.video = std::stoi(m[2]);
    view.frame = std::stoi(m[3]);
    view.category = CategoryOf(view.crop, view.instance);
    views.push_back(std::move(view));
  }
  std::sort(views.begin(), views.end(), [](const auto& a, const auto& b) { return a.crop < b.crop; });
  return views;
}

namespace {

// The largest 8-connected region of `pixels`: the edge pixels left out cut the object off from the
// patches of table or background that the mask also covers.
cv::Mat LargestRegion(const cv::Mat& pixels) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(pixels, labels, stats, centroids, 8, CV_32S);
  int largest = 0;  // Label 0 is the unmasked rest.
  for (int label = 1; label < count; ++label) {
    if (largest == 0 || stats.at<int>(label, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA))
      largest = label;
  }
  cv::Mat region = cv::Mat::zeros(pixels.size(), CV_8UC1);
  if (largest > 0) region.setTo(255, labels == largest);
  return region;
}

// The masked pixels with depth that show the object: not at a depth edge, not far from its median depth.
cv::Mat ObjectPixels(const cv::Mat& depth, const cv::Mat& mask, const RgbdObjectsCamera& camera) {
  std::vector<uint16_t> masked;
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      if (mask.at<uint8_t>(v, u) != 0 && depth.at<uint16_t>(v, u) != 0) masked.push_back(depth.at<uint16_t>(v, u));
    }
  }
  cv::Mat object = cv::Mat::zeros(depth.size(), CV_8UC1);
  if (masked.empty()) return object;
  std::nth_element(masked.begin(), masked.begin() + masked.size() / 2, masked.end());
  const double median_m = masked[masked.size() / 2] / 1000.0;
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const uint16_t mm = depth.at<uint16_t>(v, u);
      if (mask.at<uint8_t>(v, u) == 0 || mm == 0 || std::abs(mm / 1000.0 - median_m) > camera.from_median_m) continue;
      uint16_t lo = mm, hi = mm;  // The neighbourhood's depth span (pixels without depth left out).
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          const int y = v + dv, x = u + du;
          if (y < 0 || x < 0 || y >= depth.rows || x >= depth.cols || depth.at<uint16_t>(y, x) == 0) continue;
          lo = std::min(lo, depth.at<uint16_t>(y, x));
          hi = std::max(hi, depth.at<uint16_t>(y, x));
        }
      }
      if ((hi - lo) / 1000.0 <= camera.edge_jump_m) object.at<uint8_t>(v, u) = 255;
    }
  }
  return LargestRegion(object);
}

}  // namespace

perception::Cloud::Ptr ReadRgbdObjectsView(const RgbdObjectsView& view, const RgbdObjectsCamera& camera) {
  const cv::Mat colour = ReadImage(view.crop, assets::PixelFormat::kBgr8, CV_8UC3, "8-bit colour");
  const std::filesystem::path depth_file = Partner(view, "depthcrop.png"), mask_file = Partner(view, "maskcrop.png");
  const cv::Mat depth = ReadImage(depth_file, assets::PixelFormat::kGrey16, CV_16UC1, "16-bit depth in millimetres");
  const cv::Mat mask = ReadImage(mask_file, assets::PixelFormat::kGrey8, CV_8UC1, "a grey-level mask");
  for (const auto& [file, image] : {std::pair{depth_file, depth}, std::pair{mask_file, mask}}) {
    if (image.size() != colour.size()) {
      Refuse(file,
             fmt::format("{}x{}, but the colour crop is {}x{}", image.cols, image.rows, colour.cols, colour.rows));
    }
  }
  const cv::Point corner = ReadLoc(Partner(view, "loc.txt"), colour.size());
  const cv::Mat object = ObjectPixels(depth, mask, camera);
  auto cloud = std::make_shared<perception::Cloud>();
  for (int v = 0; v < colour.rows; ++v) {
    for (int u = 0; u < colour.cols; ++u) {
      if (object.at<uint8_t>(v, u) == 0) continue;
      const double z = depth.at<uint16_t>(v, u) / 1000.0;
      perception::PointT p;
      p.x = static_cast<float>((u + corner.x - camera.cx) * z / camera.focal_px);
      p.y = static_cast<float>((v + corner.y - camera.cy) * z / camera.focal_px);
      p.z = static_cast<float>(z);
      const cv::Vec3b& bgr = colour.at<cv::Vec3b>(v, u);
      p.r = bgr[2];
      p.g = bgr[1];
      p.b = bgr[0];
      cloud->push_back(p);
    }
  }
  return cloud;
}

Dataset ImportRgbdObjects(const std::filesystem::path& root, const std::filesystem::path& dir,
                          const RgbdObjectsCamera& camera) {
  const std::vector<RgbdObjectsView> views = FindRgbdObjectsViews(root);
  if (views.empty()) {
    throw std::invalid_argument("RGB-D Object Dataset folder '" + root.string() +
                                "': no <instance>_<video>_<frame>_crop.png view in it");
  }
  files::PrepareOutputDir(dir);
  std::filesystem::create_directories(dir / "clouds");
  const auto elevation = Elevations(views);
  Dataset dataset;
  dataset.object_set = root.string();
  nlohmann::json skipped = nlohmann::json::array();
  files::Progress progress("RGB-D Object Dataset views", static_cast<int>(views.size()));
  for (const RgbdObjectsView& view : views) {
    progress.Advance();
    std::string reason;
    perception::Cloud::Ptr cloud;
    try {
      cloud = ReadRgbdObjectsView(view, camera);
    } catch (const std::invalid_argument& e) {
      reason = e.what();
    }
    Sample sample;
    if (cloud && cloud->empty()) reason = "no masked pixel with depth";
    if (reason.empty()) {
      sample.parts = perception::ComputeDescriptorParts(*cloud, dataset.params);
      if (sample.parts.status != perception::DescriptorStatus::kOk) reason = sample.parts.detail;
    }
    if (!reason.empty()) {
      skipped.push_back({{"view", view.crop.string()}, {"reason", reason}});
      continue;
    }
    sample.id = static_cast<int>(dataset.samples.size());
    sample.category = view.category;
    sample.instance = view.instance;
    sample.source = "rgbd-objects";
    sample.elevation_deg = elevation.at({view.instance, view.video});
    sample.frame = view.frame;
    sample.cloud = fmt::format("clouds/{:06}.pcd", sample.id);
    perception::SaveCloud(dir / sample.cloud, *cloud);
    sample.points = static_cast<int>(cloud->size());
    sample.purity = sample.iou = 1.0;  // The dataset's own mask is the segment.
    dataset.views = std::max(dataset.views, view.frame);
    dataset.samples.push_back(std::move(sample));
  }
  progress.Finish();
  dataset.capture = {
      {"kind", "rgbd-objects"}, {"source", root.string()},
      {"views", views.size()},  {"samples", dataset.samples.size()},
      {"skipped", skipped},     {"camera", {{"focal_px", camera.focal_px}, {"cx", camera.cx}, {"cy", camera.cy}}}};
  return dataset;
}

}  // namespace sortcell::training
