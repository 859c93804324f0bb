#include "app/episode_scoring.h"

#include <cmath>

#include "app/segment_labels.h"
#include "sim/ground_truth.h"

namespace sortcell::app {
namespace {

// The table top (models/cell/cell.inc.xml). Its plane is unbounded for collision, so an object pushed
// over the edge stays at z = 0: "off the table" is judged from x and y.
constexpr double kTableMinX = -0.3, kTableMaxX = 0.9, kTableHalfY = 0.7;

nlohmann::json OrNull(const std::optional<std::string>& s) { return s ? nlohmann::json(*s) : nlohmann::json(nullptr); }

}  // namespace

EpisodeScorer::EpisodeScorer(std::vector<PlacedObject> objects, int label_count)
    : objects_(std::move(objects)), label_count_(label_count), tracks_(objects_.size()) {}

void EpisodeScorer::Observe(const cv::Mat& labels, const std::vector<DetectionRecord>& detections) {
  last_objects_.assign(detections.size(), -1);
  for (size_t i = 0; i < detections.size(); ++i) {
    const SegmentLabel truth = LabelSegment(labels, *detections[i].indices, label_count_);
    for (size_t o = 0; o < objects_.size(); ++o) {
      if (truth.label == 0 || objects_[o].label != truth.label) continue;
      last_objects_[i] = static_cast<int>(o);
      Track& t = tracks_[o];
      t.seen = true;
      if (detections[i].predicted) {
        t.predicted = detections[i].predicted;
        t.confidence = detections[i].confidence;
      }
    }
  }
}

int EpisodeScorer::ObjectOf(int detection) const {
  return detection >= 0 && detection < static_cast<int>(last_objects_.size()) ? last_objects_[detection] : -1;
}

std::pair<double, double> EpisodeScorer::GraspErrors(int detection, const Eigen::Vector2d& xy, double width,
                                                     const sim::Model& model, const sim::Data& data) const {
  const int o = ObjectOf(detection);
  if (o < 0) return {NAN, NAN};
  const sim::ObjectExtent truth = sim::ObjectExtentOf(model, data, objects_[o].body);
  return {(truth.centre_xy - xy).norm(), width - truth.width};
}

void EpisodeScorer::Unreachable(int detection) {
  const int o = ObjectOf(detection);
  if (o >= 0) tracks_[o].unreachable = true;
}

void EpisodeScorer::Attempt(const AttemptRecord& attempt) {
  ++attempts_;
  if (attempt.grasped) ++grasps_;
  const int o = ObjectOf(attempt.detection);
  if (o < 0) return;  // A detection of no placed object (a fragment, a merged pair's background).
  Track& t = tracks_[o];
  ++t.attempts;
  t.cycle_time_s += attempt.end_s - attempt.start_s;
  t.predicted = attempt.predicted;
  t.confidence = attempt.confidence;
  t.lifted = t.lifted || attempt.lifted;
}

nlohmann::json EpisodeScorer::Items(const sim::Data& data, const std::vector<std::pair<std::string, int>>& bins) const {
  nlohmann::json items = nlohmann::json::array();
  for (size_t o = 0; o < objects_.size(); ++o) {
    const PlacedObject& object = objects_[o];
    const Track& t = tracks_[o];
    const Eigen::Vector3d p = sim::BodyPose(data, object.body).translation();
    std::string outcome;
    for (const auto& [category, bin] : bins) {
      if (sim::InBin(data, object.body, bin)) outcome = category == object.category ? "sorted" : "wrong_bin";
    }
    const bool on_table = p.x() >= kTableMinX && p.x() <= kTableMaxX && std::abs(p.y()) <= kTableHalfY && p.z() > -0.05;
    if (outcome.empty()) {
      if (!on_table || t.lifted) outcome = "dropped";
      else if (t.unreachable) outcome = "unreachable";
      else if (t.attempts > 0) outcome = "grasp_failed";
      else if (!t.seen) outcome = "not_detected";
      else outcome = "left_on_table";
    }
    items.push_back({{"name", object.name},
                     {"true_category", object.category},
                     {"predicted_category", OrNull(t.predicted)},
                     {"confidence", t.predicted ? t.confidence : 0.0},
                     {"attempts", t.attempts},
                     {"outcome", outcome},
                     {"cycle_time_s", t.attempts > 0 ? nlohmann::json(t.cycle_time_s) : nlohmann::json(nullptr)},
                     {"final_xyz", {p.x(), p.y(), p.z()}}});
  }
  return items;
}

void ItemTally::Add(const nlohmann::json& item) {
  ++items;
  const std::string outcome = item["outcome"];
  ++outcomes[outcome];
  if (!item["predicted_category"].is_null()) {
    ++classified;
    if (item["predicted_category"] == item["true_category"]) ++recognised;
  }
  if ((outcome == "sorted" || outcome == "wrong_bin") && !item["cycle_time_s"].is_null()) {
    ++completed;
    cycle_s += item["cycle_time_s"].get<double>();
  }
}

int ItemTally::Count(const std::string& outcome) const {
  const auto it = outcomes.find(outcome);
  return it == outcomes.end() ? 0 : it->second;
}

nlohmann::json ItemTally::OutcomeCounts() const {
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& o : kOutcomes) counts[o] = Count(o);
  return counts;
}

nlohmann::json SummarizeEpisode(const nlohmann::json& items, int attempts, int grasps, const nlohmann::json& run) {
  ItemTally tally;
  for (const auto& item : items) tally.Add(item);
  const auto ratio = [](double a, int b) { return b > 0 ? nlohmann::json(a / b) : nlohmann::json(nullptr); };
  nlohmann::json summary = {{"items", tally.items},
                            {"outcomes", tally.OutcomeCounts()},
                            {"correct_sort_rate", ratio(tally.Count("sorted"), tally.items)},
                            {"recognition_accuracy", ratio(tally.recognised, tally.classified)},
                            {"items_classified", tally.classified},
                            {"grasp_attempts", attempts},
                            {"grasps", grasps},
                            {"grasp_success_rate", ratio(grasps, attempts)},
                            {"mean_cycle_time_s", ratio(tally.cycle_s, tally.completed)}};
  summary.update(run);
  return summary;
}

}  // namespace sortcell::app
