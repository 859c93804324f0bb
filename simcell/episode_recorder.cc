#include "simcell/episode_recorder.h"

#include <opencv2/imgproc.hpp>
#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "assets/image_file.h"
#include "perception/segment_overlay.h"
#include "sim/ground_truth.h"

namespace sortcell::simcell {

EpisodeRecorder::EpisodeRecorder(EpisodeScorer& scorer, const SimCell& cell, const sim::Model& model,
                                 const sim::Data& data, sim::VideoRecorder* video, uint64_t seed,
                                 int max_attempts_per_object, std::filesystem::path stills)
    : scorer_(scorer),
      cell_(cell),
      model_(model),
      data_(data),
      video_(video),
      seed_(seed),
      max_attempts_per_object_(max_attempts_per_object),
      tcp_site_(model.Id(mjOBJ_SITE, "tcp")) {
  stills_ = std::move(stills);
  if (!stills_.empty()) std::filesystem::create_directories(stills_);
}

void EpisodeRecorder::ShowStatus(const std::string& current) {
  if (!video_) return;
  video_->SetOverlay({fmt::format("seed {}   objects {}   frames {}", seed_, scorer_.objects().size(), cell_.frames()),
                      current,
                      fmt::format("released into bins {}   missed grasps {}   dropped {}   skipped {}", released_,
                                  missed_, dropped_, skipped_)});
}

void EpisodeRecorder::Observing() { ShowStatus("observing"); }

void EpisodeRecorder::Observed(const perception::Cloud& cloud, const cell::Observation& observation,
                               double perception_wall_s) {
  perception_wall_s_ += perception_wall_s;
  std::vector<DetectionRecord> records;
  for (const auto& d : observation.detections) records.push_back({&d.segment.indices, d.category, d.confidence});
  scorer_.Observe(cell_.last_labels(), records);
  const bool seen = observation.status == perception::SegmentationStatus::kOk;
  if ((video_ || !stills_.empty()) && seen) ShowObservation(cloud, observation.detections);
}

void EpisodeRecorder::ShowObservation(const perception::Cloud& cloud, const std::vector<cell::Detection>& detections) {
  std::vector<perception::Segment> segments;
  for (const auto& d : detections) segments.push_back(d.segment);
  cv::Mat overlay = perception::SegmentOverlay(cloud, segments);
  for (size_t i = 0; i < detections.size(); ++i) {
    // Outline and name each cluster where it is in the image.
    cv::Mat mask = cv::Mat::zeros(overlay.size(), CV_8UC1);
    for (int p : detections[i].segment.indices) mask.at<uint8_t>(p / mask.cols, p % mask.cols) = 255;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(overlay, contours, -1, cv::Scalar(255, 255, 255), 2);
    const cv::Rect box = cv::boundingRect(mask);
    const std::string text = fmt::format(
        "{} {}", i,
        detections[i].category ? fmt::format("{} {:.2f}", *detections[i].category, detections[i].confidence) : "?");
    const cv::Point at(box.x, std::max(14, box.y - 6));
    cv::putText(overlay, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
    cv::putText(overlay, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2, cv::LINE_AA);
  }
  if (video_) video_->SetInset(overlay);
  if (!stills_.empty()) {
    const auto ms = static_cast<long long>(std::llround(1000 * cell_.Now()));
    const std::filesystem::path file = stills_ / fmt::format("still_{:07d}.png", ms);
    if (!assets::WritePng(file, overlay)) throw std::runtime_error("cannot write '" + file.string() + "'");
  }
}

void EpisodeRecorder::Skipped(int detection, const cell::Detection& seen, robot::GraspStatus why) {
  if (why == robot::GraspStatus::kTooWide) {
    scorer_.Ungraspable(detection);
  } else {
    scorer_.Unreachable(detection);
  }
  ++skipped_;
  AttemptLogEntry entry;
  entry.time_s = cell_.Now();
  entry.category = seen.category.value_or("");
  entry.bin = seen.bin;
  entry.xy = {seen.footprint.centre_xy.x(), seen.footprint.centre_xy.y()};
  entry.result = std::string("skipped: ") + robot::ToString(why);
  log_.push_back(entry);
}

void EpisodeRecorder::AttemptStarting(const cell::AttemptReport& report) {
  X_TO_grasped_.reset();
  const cell::Detection& d = *report.seen;
  ShowStatus(fmt::format("object {}: {} ({:.2f})  attempt {}/{}", report.detection, *d.category, d.confidence,
                         report.attempt, max_attempts_per_object_));
  // Measured before the pick moves the object, and before the next capture (during the carry).
  truth_errors_ = scorer_.GraspErrors(report.detection, d.footprint.centre_xy, d.footprint.width, model_, data_);
  attempted_object_ = scorer_.ObjectOf(report.detection);
}

// The attempted object's position in the TCP frame now (truth), if the attempt went for one.
static std::optional<Eigen::Isometry3d> ObjectInTcp(const EpisodeScorer& scorer, int object, const sim::Data& data,
                                                    int tcp_site) {
  if (object < 0) return std::nullopt;
  const int body = scorer.objects()[object].body;
  return sim::SitePose(data, tcp_site).inverse() * sim::BodyPose(data, body);
}

void EpisodeRecorder::Grasped() { X_TO_grasped_ = ObjectInTcp(scorer_, attempted_object_, data_, tcp_site_); }

void EpisodeRecorder::Lowered() {
  const std::optional<Eigen::Isometry3d> X_TO = ObjectInTcp(scorer_, attempted_object_, data_, tcp_site_);
  if (!X_TO || !X_TO_grasped_) return;
  const double slip_mm = 1000 * (X_TO->translation() - X_TO_grasped_->translation()).norm();
  const double turn_deg = Eigen::AngleAxisd(X_TO_grasped_->linear().transpose() * X_TO->linear()).angle() * 180 / M_PI;
  slip_.max_mm = std::max(slip_.max_mm, slip_mm);
  slip_.sum_mm += slip_mm;
  slip_.max_deg = std::max(slip_.max_deg, turn_deg);
  ++slip_.carries;
  X_TO_grasped_.reset();
}

void EpisodeRecorder::AttemptEnded(const cell::AttemptReport& report) {
  const cell::Detection& d = *report.seen;
  const cell::AttemptResult result = report.pick.result;
  AttemptRecord record;
  record.object = attempted_object_;
  record.predicted = *d.category;
  record.confidence = d.confidence;
  record.start_s = report.start_s;
  record.end_s = report.end_s;
  for (const auto& span : report.phases) record.bound_s += span.bound_s;
  record.grasped = report.pick.grasped;
  record.lifted = report.pick.lifted;
  record.result = result;
  scorer_.Attempt(record);
  ++attempts_;
  for (const auto& span : report.phases) {
    phase_s_[span.phase] += span.end_s - span.start_s;
    phase_bound_s_[span.phase] += span.bound_s;
  }
  if (result == cell::AttemptResult::kReleased) ++released_;
  if (result == cell::AttemptResult::kMissed) ++missed_;
  if (result == cell::AttemptResult::kDropped) ++dropped_;

  AttemptLogEntry entry;
  entry.time_s = report.start_s;
  entry.duration_s = report.end_s - report.start_s;
  entry.category = *d.category;
  entry.bin = d.bin;
  entry.confidence = d.confidence;
  entry.xy = {d.footprint.centre_xy.x(), d.footprint.centre_xy.y()};
  entry.pinch_yaw = d.footprint.pinch_yaw;
  entry.width_m = d.footprint.width;
  entry.top_z_m = d.footprint.top_z;
  entry.lying = d.lying;
  if (report.pick.grasped) entry.release_clearance_m = report.release.clearance;
  if (report.pick.grasped) entry.max_friction_use = report.pick.max_friction_use;
  if (report.pick.recentred_m != 0) entry.recentred_m = report.pick.recentred_m;
  if (!report.pick.squeezed_harder_in.empty()) entry.squeezed_harder_in = report.pick.squeezed_harder_in;
  for (const auto& span : report.phases)
    entry.phases.push_back({span.phase, span.end_s, robot::ToString(span.hold), span.gap_m});
  entry.result = cell::ToString(result);
  if (attempted_object_ >= 0) entry.truth_object = scorer_.objects()[attempted_object_].name;
  if (truth_errors_) {
    entry.truth_centre_error_m = truth_errors_->first;
    entry.truth_width_error_m = truth_errors_->second;
  }
  if (result == cell::AttemptResult::kMotionFailed) entry.detail = report.pick.detail;
  log_.push_back(entry);
}

namespace {

std::map<std::string, double> PerAttempt(const std::map<std::string, double>& total_s, int attempts) {
  std::map<std::string, double> mean;
  for (const auto& [phase, seconds] : total_s) mean[phase] = seconds / attempts;
  return mean;
}

}  // namespace

std::map<std::string, double> EpisodeRecorder::CyclePhases() const { return PerAttempt(phase_s_, attempts_); }

std::map<std::string, double> EpisodeRecorder::CyclePhaseBounds() const {
  return PerAttempt(phase_bound_s_, attempts_);
}

}  // namespace sortcell::simcell
