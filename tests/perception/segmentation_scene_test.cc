// Segmentation on rendered Kinect frames of the cell (noise on): every object separated from the
// others is found as one segment matching its ground-truth mask with IoU >= 0.8, none is missed, and
// no segment is a piece of the table.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "files/object_set.h"
#include "cell/cell_layout.h"
#include "cell/scene_observation.h"
#include "perception/segmentation.h"
#include "sim/arm_io.h"
#include "sim/kinect_camera.h"
#include "sim/model.h"
#include "sim/object_placement.h"
#include "sim/point_cloud.h"
#include "sim/scene_composer.h"
#include "source_tree.h"

#include <opencv2/imgproc.hpp>

namespace sortcell {
namespace {

using sortcell_test::kRoot;

struct Check {
  int segments = 0, objects = 0;
  double worst_iou = 1;
  std::string report;
};

// Objects whose image region (bounding box grown by 15 px) touches no other object's: separated in
// the image too. Others may lose pixels to the Kinect's projector shadow of the object in front.
std::map<int, bool> SeparatedInImage(const cv::Mat& labels, const std::map<int, int>& mask) {
  std::map<int, cv::Rect> box;
  for (const auto& [label, pixels] : mask) box[label] = cv::boundingRect(labels == label);
  std::map<int, bool> separated;
  for (const auto& [a, ra] : box) {
    separated[a] = true;
    const cv::Rect grown(ra.x - 15, ra.y - 15, ra.width + 30, ra.height + 30);
    for (const auto& [b, rb] : box) {
      if (a != b && (grown & rb).area() > 0) separated[a] = false;
    }
  }
  return separated;
}

// Matches segments to the label image and checks the rules above.
// A capture with the simulator's truth beside it, for checks against ground truth.
struct Shot : sim::KinectFrame {
  cv::Mat labels;
  Eigen::Isometry3d X_WC;
};
Shot Shoot(sim::KinectCamera& kinect, const sim::Data& data, const sim::KinectNoiseParams* noise,
           std::mt19937_64* rng) {
  sim::FrameTruth truth;
  Shot shot{kinect.Capture(data, noise, rng, &truth), truth.labels, truth.X_WC};
  return shot;
}

Check Evaluate(const perception::SegmentationResult& r, const Shot& frame, const std::vector<std::string>& names) {
  Check c;
  std::map<int, int> mask;
  for (auto it = frame.labels.begin<uint16_t>(); it != frame.labels.end<uint16_t>(); ++it) {
    if (*it > 0) ++mask[*it];
  }
  const std::map<int, bool> separated = SeparatedInImage(frame.labels, mask);
  std::map<int, int> matched;
  for (const auto& s : r.segments) {
    std::map<int, int> votes;
    for (int i : s.indices) ++votes[frame.labels.at<uint16_t>(i / frame.labels.cols, i % frame.labels.cols)];
    const auto best =
        std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    EXPECT_NE(best->first, 0) << "a segment of " << s.indices.size() << " px is not an object (table piece?)";
    if (best->first == 0) continue;
    EXPECT_EQ(matched.count(best->first), 0u) << names[best->first - 1] << " split into two segments";
    const double iou = static_cast<double>(best->second) / (mask[best->first] + s.indices.size() - best->second);
    matched[best->first] = 1;
    c.worst_iou = std::min(c.worst_iou, iou);
    c.report += names[best->first - 1] + " IoU " + std::to_string(iou) +
                (separated.at(best->first) ? "" : " (overlapping in the image)") + "; ";
    EXPECT_GE(iou, separated.at(best->first) ? 0.8 : 0.5) << names[best->first - 1];
  }
  for (const auto& [label, pixels] : mask) {
    if (pixels < 150) continue;  // A sliver behind another object is not a separated object.
    ++c.objects;
    EXPECT_EQ(matched.count(label), 1u) << names[label - 1] << " (" << pixels << " px) was missed";
  }
  c.segments = static_cast<int>(r.segments.size());
  return c;
}

TEST(SegmentationScene, CellSceneEveryObjectFoundWithAndWithoutBackground) {
  const sim::Model model = sim::Model::FromFile((kRoot / "scenes/cell.xml").string());
  sim::Data data(model);
  sim::KinectCamera kinect(model);
  const sim::KinectNoiseParams noise;
  std::mt19937_64 rng(7);
  const std::vector<std::string> names = kinect.object_names();
  int slot = 0;
  sim::ResetToObserve(model, data);
  for (const auto& name : names) sim::ParkObject(model, data, model.Id(mjOBJ_BODY, name), slot++);
  mj_forward(model.get(), data.get());
  const auto background = sim::ToOrganizedCloud(kinect.Capture(data, &noise, &rng));
  sim::ResetToObserve(model, data);
  mj_forward(model.get(), data.get());
  const Shot frame = Shoot(kinect, data, &noise, &rng);
  const auto cloud = sim::ToOrganizedCloud(frame);
  for (const bool subtract : {false, true}) {
    const auto r = perception::SegmentObjects(*cloud, frame.X_WC, subtract ? background.get() : nullptr);
    const Check c = Evaluate(r, frame, names);
    EXPECT_EQ(c.objects, 6);
    EXPECT_EQ(c.segments, 6) << c.report;
    std::cout << (subtract ? "with" : "without") << " background: " << c.report << "\n";
  }
  // The cell's own segmentation (convex clusters): one segment per object too; the cup's inside, seen
  // over its rim, joins its wall.
  const auto r =
      perception::SegmentObjects(*cloud, frame.X_WC, background.get(), cell::CellSegmentation(cell::CellLayout()));
  const Check c = Evaluate(r, frame, names);
  EXPECT_EQ(c.objects, 6);
  EXPECT_EQ(c.segments, 6) << c.report;
}

TEST(SegmentationScene, RandomArrangementsOfThePaperObjects) {
  const files::ObjectSet set = files::LoadObjectSet(kRoot / "scenes/objects/paper.yaml");
  std::vector<std::filesystem::path> models;
  for (const auto& o : set.objects) models.push_back(o.model);
  const sim::Model model = sim::LoadComposedCell(kRoot / "models", models, "paper set");
  sim::Data data(model);
  sim::ArmIo(model).SetArmPosition(data, cell::CellLayout().q_observe);
  sim::KinectCamera kinect(model);
  const sim::KinectNoiseParams noise;
  std::vector<int> bodies;
  std::vector<double> radii;
  for (const auto& o : set.objects) {
    bodies.push_back(model.Id(mjOBJ_BODY, o.name));
    radii.push_back(sim::ObjectShapeOf(model, bodies.back()).disc_radius);
  }
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    std::mt19937_64 rng(seed);
    const auto poses = sim::SampleTablePoses(radii, {0.32, -0.22}, {0.68, 0.22}, 0.03, rng);
    ASSERT_TRUE(poses.has_value());
    for (size_t i = 0; i < bodies.size(); ++i) {
      sim::PlaceObject(model, data, bodies[i], (*poses)[i].x, (*poses)[i].y, (*poses)[i].yaw);
    }
    mj_forward(model.get(), data.get());
    const Shot frame = Shoot(kinect, data, &noise, &rng);
    const auto r = perception::SegmentObjects(*sim::ToOrganizedCloud(frame), frame.X_WC, nullptr);
    const Check c = Evaluate(r, frame, kinect.object_names());
    EXPECT_GE(c.objects, 5) << "seed " << seed;
    EXPECT_EQ(c.segments, c.objects) << "seed " << seed << ": " << c.report;
    std::cout << "seed " << seed << ": " << c.report << "\n";
  }
}

}  // namespace
}  // namespace sortcell
