#include "simcell/episode_scoring.h"

#include "simcell/segment_labels.h"

namespace sortcell::simcell {

EpisodeScorer::EpisodeScorer(std::vector<PlacedObject> objects, int label_count, const TableExtent& table,
                             cell::SortingRules rules)
    : objects_(std::move(objects)),
      label_count_(label_count),
      table_(table),
      rules_(std::move(rules)),
      tracks_(objects_.size()) {}

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

std::optional<std::pair<double, double>> EpisodeScorer::GraspErrors(int detection, const Eigen::Vector2d& xy,
                                                                    double width, const sim::Model& model,
                                                                    const sim::Data& data) const {
  const int o = ObjectOf(detection);
  if (o < 0) return std::nullopt;
  const sim::ObjectExtent truth = sim::ObjectExtentOf(model, data, objects_[o].body);
  return std::make_pair((truth.centre_xy - xy).norm(), width - truth.width);
}

void EpisodeScorer::Unreachable(int detection) {
  const int o = ObjectOf(detection);
  if (o >= 0) tracks_[o].unreachable = true;
}

void EpisodeScorer::Ungraspable(int detection) {
  const int o = ObjectOf(detection);
  if (o >= 0) tracks_[o].ungraspable = true;
}

void EpisodeScorer::Attempt(const AttemptRecord& attempt) {
  ++attempts_;
  if (attempt.grasped) ++grasps_;
  const int o = attempt.object;
  if (o < 0) return;  // A detection of no placed object (a fragment, a merged pair's background).
  Track& t = tracks_[o];
  ++t.attempts;
  t.cycle_time_s += attempt.end_s - attempt.start_s;
  t.cycle_bound_s += attempt.bound_s;
  t.predicted = attempt.predicted;
  t.confidence = attempt.confidence;
  // Put back because its bin is out of reach: it stands on the table again (whatever happened to it
  // before), given up as unreachable.
  if (attempt.result == cell::AttemptResult::kPutBack) {
    t.unreachable = true;
    t.lifted = false;
  } else {
    t.lifted = t.lifted || attempt.lifted;
  }
}

std::optional<sim::BinRef> EpisodeScorer::BinHolding(size_t o, const sim::Data& data,
                                                     const std::vector<sim::BinRef>& bins) const {
  for (const auto& bin : bins) {
    if (sim::InBin(data, objects_[o].body, bin)) return bin;
  }
  return std::nullopt;
}

cell::ItemOutcome EpisodeScorer::OutcomeOf(size_t o, const sim::Data& data,
                                           const std::optional<sim::BinRef>& in_bin) const {
  const PlacedObject& object = objects_[o];
  const Track& t = tracks_[o];
  if (in_bin) return in_bin->name == object.bin ? cell::ItemOutcome::kSorted : cell::ItemOutcome::kWrongBin;
  const Eigen::Vector3d p = sim::BodyPose(data, object.body).translation();
  const bool on_table = (p.head<2>().array() >= table_.min_xy.array()).all() &&
                        (p.head<2>().array() <= table_.max_xy.array()).all() && p.z() > -0.05;
  if (!on_table || t.lifted) return cell::ItemOutcome::kDropped;
  if (t.unreachable) return cell::ItemOutcome::kUnreachable;
  if (t.ungraspable) return cell::ItemOutcome::kUngraspable;
  if (t.attempts > 0) return cell::ItemOutcome::kGraspFailed;
  if (!t.seen) return cell::ItemOutcome::kNotDetected;
  return cell::ItemOutcome::kLeftOnTable;
}

std::vector<ItemResult> EpisodeScorer::Items(const sim::Data& data, const std::vector<sim::BinRef>& bins) const {
  std::vector<ItemResult> items;
  for (size_t o = 0; o < objects_.size(); ++o) {
    const Track& t = tracks_[o];
    const Eigen::Vector3d p = sim::BodyPose(data, objects_[o].body).translation();
    ItemResult item;
    item.name = objects_[o].name;
    item.true_category = objects_[o].category;
    item.predicted_category = t.predicted;
    item.confidence = t.predicted ? t.confidence : 0.0;
    item.attempts = t.attempts;
    const std::optional<sim::BinRef> in_bin = BinHolding(o, data, bins);
    item.outcome = OutcomeOf(o, data, in_bin);
    item.rule_bin = objects_[o].bin;
    if (in_bin) item.bin = in_bin->name;
    item.unknown = objects_[o].unknown;
    item.rejected = t.predicted && rules_.Rejects(t.confidence);
    if (t.attempts > 0) {
      item.cycle_time_s = t.cycle_time_s;
      item.cycle_bound_s = t.cycle_bound_s;
    }
    item.final_xyz = {p.x(), p.y(), p.z()};
    items.push_back(item);
  }
  return items;
}

}  // namespace sortcell::simcell
