#include "app/episode/episode_metrics.h"

#include <spdlog/fmt/fmt.h>

#include "app/common/json_fields.h"

namespace sortcell::app {

void ItemTally::Add(const ItemResult& item) {
  ++items;
  ++outcomes[item.outcome];
  if (item.unknown) {
    ++unknown;
    unknown_rejected += item.outcome == cell::ItemOutcome::kSorted;  // Its bin is the reject bin.
    unknown_in_category_bin += item.outcome == cell::ItemOutcome::kWrongBin;
  } else {
    ++known;
    known_rejected += item.rejected;
  }
  if (item.predicted_category) {
    ++classified;
    if (*item.predicted_category == item.true_category) ++recognised;
  }
  const bool in_a_bin = item.outcome == cell::ItemOutcome::kSorted || item.outcome == cell::ItemOutcome::kWrongBin;
  if (in_a_bin && item.cycle_time_s) {
    ++completed;
    cycle_s += *item.cycle_time_s;
    if (item.cycle_bound_s) {
      ++bounded;
      bounded_cycle_s += *item.cycle_time_s;
      cycle_bound_s += *item.cycle_bound_s;
    }
  }
}

int ItemTally::Count(cell::ItemOutcome outcome) const {
  const auto it = outcomes.find(outcome);
  return it == outcomes.end() ? 0 : it->second;
}

std::optional<double> Ratio(double a, int b) { return b > 0 ? std::optional<double>(a / b) : std::nullopt; }

std::optional<double> ItemTally::MeanCycleBound() const { return Ratio(cycle_bound_s, bounded); }

std::optional<double> ItemTally::CycleToBound() const {
  return cycle_bound_s > 0 ? std::optional<double>(bounded_cycle_s / cycle_bound_s) : std::nullopt;
}

std::optional<double> PicksPerHour(int sorted, double sim_time_s) {
  return sim_time_s > 0 ? std::optional<double>(3600.0 * sorted / sim_time_s) : std::nullopt;
}

EpisodeSummary SummarizeEpisode(const std::vector<ItemResult>& items, int attempts, int grasps, const RunFigures& run) {
  ItemTally tally;
  for (const auto& item : items) tally.Add(item);
  EpisodeSummary s;
  s.items = tally.items;
  for (const auto outcome : cell::kItemOutcomes) s.outcomes[outcome] = tally.Count(outcome);
  s.correct_sort_rate = Ratio(tally.Count(cell::ItemOutcome::kSorted), tally.items);
  s.recognition_accuracy = Ratio(tally.recognised, tally.classified);
  s.items_classified = tally.classified;
  s.grasp_attempts = attempts;
  s.grasps = grasps;
  s.grasp_success_rate = Ratio(grasps, attempts);
  s.mean_cycle_time_s = Ratio(tally.cycle_s, tally.completed);
  s.mean_cycle_bound_s = tally.MeanCycleBound();
  s.cycle_to_bound = tally.CycleToBound();
  s.picks_per_hour = PicksPerHour(tally.Count(cell::ItemOutcome::kSorted), run.sim_time_s);
  s.run = run;
  return s;
}

std::string EpisodeParagraph(const EpisodeMetrics& metrics) {
  const EpisodeSummary& s = metrics.summary;
  const auto rate = [](const std::optional<double>& v) {
    return v ? fmt::format("{:.0f} %", 100 * *v) : std::string("n/a");
  };
  std::string text = fmt::format("Episode (seed {}, {} objects): {} sorted into the right bin ({})", metrics.seed,
                                 s.items, s.outcomes.at(cell::ItemOutcome::kSorted), rate(s.correct_sort_rate));
  for (const auto outcome : cell::kItemOutcomes) {
    const int n = s.outcomes.at(outcome);
    if (outcome != cell::ItemOutcome::kSorted && n > 0) text += fmt::format(", {} {}", n, cell::ToString(outcome));
  }
  text +=
      fmt::format(". Recognition accuracy {}, grasp success {} of {} attempts, {}{}. ", rate(s.recognition_accuracy),
                  rate(s.grasp_success_rate), s.grasp_attempts,
                  s.mean_cycle_time_s
                      ? fmt::format("mean cycle {:.1f} s per item", *s.mean_cycle_time_s) +
                            (s.cycle_to_bound ? fmt::format(" ({:.1f} times the arm's least time)", *s.cycle_to_bound)
                                              : std::string())
                      : std::string("no completed pick"),
                  s.picks_per_hour ? fmt::format(" ({:.0f} picks per hour)", *s.picks_per_hour) : std::string());
  text += fmt::format(
      "{:.1f} s simulated in {:.1f} s (real-time factor {:.1f}), perception {:.0f} ms per frame over {} "
      "frames, status {}.",
      s.run.sim_time_s, s.run.wall_time_s, s.run.real_time_factor, s.run.perception_ms_per_frame, s.run.frames,
      cell::ToString(s.run.status));
  return text;
}

nlohmann::json OutcomeCountsJson(const OutcomeCounts& counts) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto outcome : cell::kItemOutcomes) {
    const auto it = counts.find(outcome);
    j[cell::ToString(outcome)] = it == counts.end() ? 0 : it->second;
  }
  return j;
}

void to_json(nlohmann::json& j, const ItemResult& v) {
  j = {{"name", v.name},
       {"true_category", v.true_category},
       {"predicted_category", OrNull(v.predicted_category)},
       {"confidence", v.confidence},
       {"attempts", v.attempts},
       {"outcome", v.outcome},
       {"cycle_time_s", OrNull(v.cycle_time_s)},
       {"cycle_bound_s", OrNull(v.cycle_bound_s)},
       {"final_xyz", v.final_xyz}};
  // Records from before the cell files (no rule bin) are written back as they were read.
  if (!v.rule_bin.empty()) {
    j["rule_bin"] = v.rule_bin;
    j["bin"] = v.bin;
    j["unknown"] = v.unknown;
    j["rejected"] = v.rejected;
  }
}

void from_json(const nlohmann::json& j, ItemResult& v) {
  ReadField(j, "", "name", v.name);
  ReadField(j, "", "true_category", v.true_category);
  ReadNullable(j, "", "predicted_category", v.predicted_category);
  ReadField(j, "", "confidence", v.confidence);
  ReadField(j, "", "attempts", v.attempts);
  ReadField(j, "", "outcome", v.outcome);
  ReadNullable(j, "", "cycle_time_s", v.cycle_time_s);
  ReadAddedNullable(j, "", "cycle_bound_s", v.cycle_bound_s);
  ReadField(j, "", "final_xyz", v.final_xyz);
  ReadAddedField(j, "", "rule_bin", v.rule_bin);
  ReadAddedField(j, "", "bin", v.bin);
  ReadAddedField(j, "", "unknown", v.unknown);
  ReadAddedField(j, "", "rejected", v.rejected);
}

void to_json(nlohmann::json& j, const EpisodeSummary& v) {
  j = {{"items", v.items},
       {"outcomes", OutcomeCountsJson(v.outcomes)},
       {"correct_sort_rate", OrNull(v.correct_sort_rate)},
       {"recognition_accuracy", OrNull(v.recognition_accuracy)},
       {"items_classified", v.items_classified},
       {"grasp_attempts", v.grasp_attempts},
       {"grasps", v.grasps},
       {"grasp_success_rate", OrNull(v.grasp_success_rate)},
       {"mean_cycle_time_s", OrNull(v.mean_cycle_time_s)},
       {"mean_cycle_bound_s", OrNull(v.mean_cycle_bound_s)},
       {"cycle_to_bound", OrNull(v.cycle_to_bound)},
       {"picks_per_hour", OrNull(v.picks_per_hour)},
       // The run's own figures, flat beside the counts.
       {"status", v.run.status},
       {"sim_time_s", v.run.sim_time_s},
       {"wall_time_s", v.run.wall_time_s},
       {"real_time_factor", v.run.real_time_factor},
       {"frames", v.run.frames},
       {"perception_ms_per_frame", v.run.perception_ms_per_frame},
       {"render_ms_per_frame", v.run.render_ms_per_frame},
       {"video_frames", v.run.video_frames},
       {"video_render_wall_s", v.run.video_render_wall_s},
       {"mujoco_warnings", v.run.mujoco_warnings},
       {"cycle_phases_s", v.run.cycle_phases_s},
       {"cycle_phases_bound_s", v.run.cycle_phases_bound_s},
       {"profile_wall_s", v.run.profile_wall_s},
       {"physics_profile", v.run.physics_profile},
       {"tracking_max_error_rad", v.run.tracking_max_error_rad},
       {"torque_saturated_samples", v.run.torque_saturated_samples},
       {"carry_slip_max_mm", v.run.carry_slip_max_mm},
       {"carry_slip_mean_mm", v.run.carries > 0 ? v.run.carry_slip_sum_mm / v.run.carries : 0.0},
       {"carry_turn_max_deg", v.run.carry_turn_max_deg},
       {"carries", v.run.carries},
       {"calibration", OrNull(v.calibration)}};
}

void from_json(const nlohmann::json& j, EpisodeSummary& v) {
  const std::string path = "summary";
  ReadField(j, path, "items", v.items);
  nlohmann::json outcomes;
  ReadField(j, path, "outcomes", outcomes);
  v.outcomes.clear();
  for (const auto outcome : cell::kItemOutcomes) {
    // `ungraspable` came later: records written before it have none (0).
    v.outcomes[outcome] = 0;
    if (outcome == cell::ItemOutcome::kUngraspable) {
      ReadAddedField(outcomes, path + ".outcomes", cell::ToString(outcome), v.outcomes[outcome]);
    } else {
      ReadField(outcomes, path + ".outcomes", cell::ToString(outcome), v.outcomes[outcome]);
    }
  }
  ReadNullable(j, path, "correct_sort_rate", v.correct_sort_rate);
  ReadNullable(j, path, "recognition_accuracy", v.recognition_accuracy);
  ReadField(j, path, "items_classified", v.items_classified);
  ReadField(j, path, "grasp_attempts", v.grasp_attempts);
  ReadField(j, path, "grasps", v.grasps);
  ReadNullable(j, path, "grasp_success_rate", v.grasp_success_rate);
  ReadNullable(j, path, "mean_cycle_time_s", v.mean_cycle_time_s);
  ReadField(j, path, "status", v.run.status);
  ReadField(j, path, "sim_time_s", v.run.sim_time_s);
  ReadField(j, path, "wall_time_s", v.run.wall_time_s);
  ReadField(j, path, "real_time_factor", v.run.real_time_factor);
  ReadField(j, path, "frames", v.run.frames);
  ReadField(j, path, "perception_ms_per_frame", v.run.perception_ms_per_frame);
  ReadField(j, path, "render_ms_per_frame", v.run.render_ms_per_frame);
  ReadField(j, path, "video_frames", v.run.video_frames);
  ReadField(j, path, "video_render_wall_s", v.run.video_render_wall_s);
  ReadField(j, path, "mujoco_warnings", v.run.mujoco_warnings);
  // Added later: records written before them still read.
  v.picks_per_hour = PicksPerHour(v.outcomes.at(cell::ItemOutcome::kSorted), v.run.sim_time_s);
  ReadAddedField(j, path, "cycle_phases_s", v.run.cycle_phases_s);
  ReadAddedField(j, path, "cycle_phases_bound_s", v.run.cycle_phases_bound_s);
  ReadAddedNullable(j, path, "mean_cycle_bound_s", v.mean_cycle_bound_s);
  ReadAddedNullable(j, path, "cycle_to_bound", v.cycle_to_bound);
  ReadAddedField(j, path, "profile_wall_s", v.run.profile_wall_s);
  ReadAddedField(j, path, "physics_profile", v.run.physics_profile);
  ReadAddedField(j, path, "tracking_max_error_rad", v.run.tracking_max_error_rad);
  ReadAddedField(j, path, "torque_saturated_samples", v.run.torque_saturated_samples);
  ReadAddedField(j, path, "carry_slip_max_mm", v.run.carry_slip_max_mm);
  ReadAddedField(j, path, "carries", v.run.carries);
  ReadAddedField(j, path, "carry_turn_max_deg", v.run.carry_turn_max_deg);
  double mean_mm = 0;
  ReadAddedField(j, path, "carry_slip_mean_mm", mean_mm);
  v.run.carry_slip_sum_mm = mean_mm * v.run.carries;
  v.calibration.reset();
  if (j.contains("calibration")) ReadNullable(j, path, "calibration", v.calibration);
}

void to_json(nlohmann::json& j, const CalibrationFigures& v) {
  j = {{"status", v.status},
       {"sightings", v.sightings},
       {"inliers", v.inliers},
       {"rms_residual_m", v.rms_residual_m},
       {"duration_s", v.duration_s},
       {"error_m", v.error_m},
       {"error_rad", v.error_rad},
       {"prior_error_m", v.prior_error_m},
       {"prior_error_rad", v.prior_error_rad}};
}

void from_json(const nlohmann::json& j, CalibrationFigures& v) {
  const std::string path;  // ReadField names the record: "summary.calibration: <key>: ...".
  ReadField(j, path, "status", v.status);
  ReadField(j, path, "sightings", v.sightings);
  ReadField(j, path, "inliers", v.inliers);
  ReadField(j, path, "rms_residual_m", v.rms_residual_m);
  ReadField(j, path, "duration_s", v.duration_s);
  ReadField(j, path, "error_m", v.error_m);
  ReadField(j, path, "error_rad", v.error_rad);
  ReadField(j, path, "prior_error_m", v.prior_error_m);
  ReadField(j, path, "prior_error_rad", v.prior_error_rad);
}

void to_json(nlohmann::json& j, const EpisodeVariation& v) {
  j = {{"light_intensity", v.light_intensity}, {"noise_scale", v.noise_scale},
       {"friction_scale", v.friction_scale},   {"mass_scale", v.mass_scale},
       {"camera_shift_m", v.camera_shift_m},   {"camera_turn_rad", v.camera_turn_rad},
       {"colour_jitter", v.colour_jitter}};
}

void to_json(nlohmann::json& j, const AttemptLogEntry& v) {
  j = {{"time_s", v.time_s}, {"category", v.category}, {"bin", v.bin}, {"xy", v.xy}, {"result", v.result}};
  // A skipped cluster has no attempt figures; an attempt has all of them.
  if (!v.duration_s) return;
  j["duration_s"] = *v.duration_s;
  j["confidence"] = OrNull(v.confidence);
  j["pinch_yaw"] = OrNull(v.pinch_yaw);
  j["width_m"] = OrNull(v.width_m);
  j["top_z_m"] = OrNull(v.top_z_m);
  j["lying"] = OrNull(v.lying);
  j["release_clearance_m"] = OrNull(v.release_clearance_m);
  nlohmann::json phases = nlohmann::json::array();
  for (const auto& p : v.phases)
    phases.push_back({{"phase", p.phase}, {"end_s", p.end_s}, {"hold", p.hold}, {"gap_m", p.gap_m}});
  j["phases"] = phases;
  j["max_friction_use"] = OrNull(v.max_friction_use);
  j["recentred_m"] = OrNull(v.recentred_m);
  j["squeezed_harder_in"] = OrNull(v.squeezed_harder_in);
  j["truth_object"] = OrNull(v.truth_object);
  j["truth_centre_error_m"] = OrNull(v.truth_centre_error_m);
  j["truth_width_error_m"] = OrNull(v.truth_width_error_m);
  j["detail"] = v.detail;
}

void from_json(const nlohmann::json& j, AttemptLogEntry& v) {
  v = AttemptLogEntry{};
  ReadField(j, "", "time_s", v.time_s);
  ReadField(j, "", "category", v.category);
  ReadField(j, "", "bin", v.bin);
  ReadField(j, "", "xy", v.xy);
  ReadField(j, "", "result", v.result);
  if (!j.contains("duration_s")) return;  // A skipped cluster.
  double duration = 0;
  ReadField(j, "", "duration_s", duration);
  v.duration_s = duration;
  ReadNullable(j, "", "confidence", v.confidence);
  ReadNullable(j, "", "pinch_yaw", v.pinch_yaw);
  ReadNullable(j, "", "width_m", v.width_m);
  ReadNullable(j, "", "top_z_m", v.top_z_m);
  ReadNullable(j, "", "lying", v.lying);
  ReadNullable(j, "", "release_clearance_m", v.release_clearance_m);
  nlohmann::json phases;
  ReadField(j, "", "phases", phases);
  if (!phases.is_array()) throw std::invalid_argument("phases: expected a list");
  for (size_t i = 0; i < phases.size(); ++i) {
    const std::string where = "phases[" + std::to_string(i) + "]";
    PhaseHold p;
    ReadField(phases[i], where, "phase", p.phase);
    ReadField(phases[i], where, "end_s", p.end_s);
    ReadField(phases[i], where, "hold", p.hold);
    ReadField(phases[i], where, "gap_m", p.gap_m);
    v.phases.push_back(p);
  }
  ReadNullable(j, "", "max_friction_use", v.max_friction_use);
  ReadNullable(j, "", "recentred_m", v.recentred_m);
  ReadNullable(j, "", "squeezed_harder_in", v.squeezed_harder_in);
  ReadNullable(j, "", "truth_object", v.truth_object);
  ReadNullable(j, "", "truth_centre_error_m", v.truth_centre_error_m);
  ReadNullable(j, "", "truth_width_error_m", v.truth_width_error_m);
  ReadField(j, "", "detail", v.detail);
}

void to_json(nlohmann::json& j, const EpisodeMetrics& v) {
  j = {{"seed", v.seed},       {"scene", v.scene},           {"cell", v.cell},           {"object_set", v.object_set},
       {"model", v.model},     {"descriptor", v.descriptor}, {"variation", v.variation}, {"items", v.items},
       {"summary", v.summary}, {"attempts", v.attempts},     {"video", OrNull(v.video)}};
}

}  // namespace sortcell::app
