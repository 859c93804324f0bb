#include "simcell/episode_metrics.h"

#include <spdlog/fmt/fmt.h>

#include "files/json_fields.h"
#include "files/record_fields.h"

namespace sortcell::simcell {

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
  return SummarizeTally(tally, attempts, grasps, run);
}

EpisodeSummary SummarizeTally(const ItemTally& tally, int attempts, int grasps, const RunFigures& run) {
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

struct ItemResultFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("name", v.name);
    field("true_category", v.true_category);
    field("predicted_category", v.predicted_category);
    field("confidence", v.confidence);
    field("attempts", v.attempts);
    field("outcome", v.outcome);
    field("cycle_time_s", v.cycle_time_s);
    field("cycle_bound_s", v.cycle_bound_s, files::kAdded);
    field("final_xyz", v.final_xyz);
  }
};
ItemResultFields RecordFieldsOf(const ItemResult*);

// What the cell files added: written only with a rule bin, so that records from before them are written
// back as they were read.
struct ItemBinFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("rule_bin", v.rule_bin, files::kAdded);
    field("bin", v.bin, files::kAdded);
    field("unknown", v.unknown, files::kAdded);
    field("rejected", v.rejected, files::kAdded);
  }
};

void to_json(nlohmann::json& j, const ItemResult& v) {
  files::WriteFields(j, v);
  if (!v.rule_bin.empty()) files::WriteFields(j, v, ItemBinFields{});
}

void from_json(const nlohmann::json& j, ItemResult& v) {
  files::ReadFields(j, "", v);
  files::ReadFields(j, "", v, ItemBinFields{});
}

// The summary's own figures; the run's (RunFigures) are written flat beside them.
struct SummaryFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("items", v.items);
    field("correct_sort_rate", v.correct_sort_rate);
    field("recognition_accuracy", v.recognition_accuracy);
    field("items_classified", v.items_classified);
    field("grasp_attempts", v.grasp_attempts);
    field("grasps", v.grasps);
    field("grasp_success_rate", v.grasp_success_rate);
    field("mean_cycle_time_s", v.mean_cycle_time_s);
    field("mean_cycle_bound_s", v.mean_cycle_bound_s, files::kAdded);
    field("cycle_to_bound", v.cycle_to_bound, files::kAdded);
    // A sweep sums its episodes' calibrations up apart.
    field("calibration", v.calibration, files::kAdded | files::kUnpooled);
  }
};

nlohmann::json SummaryJson(const EpisodeSummary& s, bool pooled_run_only) {
  nlohmann::json j;
  if (pooled_run_only) {
    files::WriteFieldsWithout(j, s, files::kUnpooled, SummaryFields{});
    files::WriteFieldsWith(j, s.run, files::kPooled);
  } else {
    files::WriteFields(j, s, SummaryFields{});
    files::WriteFields(j, s.run);
  }
  j["outcomes"] = OutcomeCountsJson(s.outcomes);
  j["picks_per_hour"] = files::OrNull(s.picks_per_hour);
  j["carry_slip_mean_mm"] = s.run.carries > 0 ? s.run.carry_slip_sum_mm / s.run.carries : 0.0;
  return j;
}

void to_json(nlohmann::json& j, const EpisodeSummary& v) { j = SummaryJson(v, false); }

void PoolRunFigures(RunFigures& pooled, const RunFigures& run, int attempts) {
  files::PoolFields(pooled, run, attempts);
  pooled.carry_slip_sum_mm += run.carry_slip_sum_mm;  // Not a key: metrics.json carries the mean.
}

void FinishRunPool(RunFigures& pooled, int attempts) {
  files::FinishPool(pooled, attempts);
  pooled.real_time_factor = RealTimeFactor(pooled.sim_time_s, pooled.wall_time_s);
}

double RealTimeFactor(double sim_time_s, double wall_time_s) { return wall_time_s > 0 ? sim_time_s / wall_time_s : 0; }

void from_json(const nlohmann::json& j, EpisodeSummary& v) {
  const std::string path = "summary";
  v.calibration.reset();
  files::ReadFields(j, path, v, SummaryFields{});
  files::ReadFields(j, path, v.run);
  nlohmann::json outcomes;
  files::ReadField(j, path, "outcomes", outcomes);
  v.outcomes.clear();
  for (const auto outcome : cell::kItemOutcomes) {
    // `ungraspable` came later: records written before it have none (0).
    v.outcomes[outcome] = 0;
    files::ReadByRule(outcomes, path + ".outcomes", cell::ToString(outcome), v.outcomes[outcome],
                      outcome == cell::ItemOutcome::kUngraspable ? files::kAdded : files::kRequired);
  }
  // Derived, not read: records from before it still have it.
  v.picks_per_hour = PicksPerHour(v.outcomes.at(cell::ItemOutcome::kSorted), v.run.sim_time_s);
  double mean_mm = 0;
  files::ReadAddedField(j, path, "carry_slip_mean_mm", mean_mm);
  v.run.carry_slip_sum_mm = mean_mm * v.run.carries;
}

struct CalibrationFiguresFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("status", v.status);
    field("sightings", v.sightings);
    field("inliers", v.inliers);
    field("rms_residual_m", v.rms_residual_m);
    field("duration_s", v.duration_s);
    field("error_m", v.error_m);
    field("error_rad", v.error_rad);
    field("prior_error_m", v.prior_error_m);
    field("prior_error_rad", v.prior_error_rad);
  }
};
CalibrationFiguresFields RecordFieldsOf(const CalibrationFigures*);

void to_json(nlohmann::json& j, const CalibrationFigures& v) { files::WriteFields(j, v); }

// ReadField names the record: "summary.calibration: <key>: ...".
void from_json(const nlohmann::json& j, CalibrationFigures& v) { files::ReadFields(j, "", v); }

struct EpisodeVariationFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("light_intensity", v.light_intensity);
    field("noise_scale", v.noise_scale);
    field("friction_scale", v.friction_scale);
    field("mass_scale", v.mass_scale);
    field("camera_shift_m", v.camera_shift_m);
    field("camera_turn_rad", v.camera_turn_rad);
    field("colour_jitter", v.colour_jitter);
  }
};
EpisodeVariationFields RecordFieldsOf(const EpisodeVariation*);

void to_json(nlohmann::json& j, const EpisodeVariation& v) { files::WriteFields(j, v); }

struct PhaseHoldFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("phase", v.phase);
    field("end_s", v.end_s);
    field("hold", v.hold);
    field("gap_m", v.gap_m);
  }
};
PhaseHoldFields RecordFieldsOf(const PhaseHold*);

void to_json(nlohmann::json& j, const PhaseHold& v) { files::WriteFields(j, v); }

// Every line of the log: an attempt or a skipped cluster.
struct AttemptLogEntryFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("time_s", v.time_s);
    field("category", v.category);
    field("bin", v.bin);
    field("xy", v.xy);
    field("result", v.result);
  }
};
AttemptLogEntryFields RecordFieldsOf(const AttemptLogEntry*);

// An attempt's figures (beside its duration_s and phases), which a skipped cluster has none of.
struct AttemptFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("confidence", v.confidence);
    field("pinch_yaw", v.pinch_yaw);
    field("width_m", v.width_m);
    field("top_z_m", v.top_z_m);
    field("lying", v.lying);
    field("release_clearance_m", v.release_clearance_m);
    field("max_friction_use", v.max_friction_use);
    field("recentred_m", v.recentred_m);
    field("squeezed_harder_in", v.squeezed_harder_in);
    field("truth_object", v.truth_object);
    field("truth_centre_error_m", v.truth_centre_error_m);
    field("truth_width_error_m", v.truth_width_error_m);
    field("detail", v.detail);
  }
};

void to_json(nlohmann::json& j, const AttemptLogEntry& v) {
  files::WriteFields(j, v);
  if (!v.duration_s) return;
  j["duration_s"] = *v.duration_s;
  j["phases"] = v.phases;
  files::WriteFields(j, v, AttemptFields{});
}

void from_json(const nlohmann::json& j, AttemptLogEntry& v) {
  v = AttemptLogEntry{};
  files::ReadFields(j, "", v);
  if (!j.contains("duration_s")) return;  // A skipped cluster.
  double duration = 0;
  files::ReadField(j, "", "duration_s", duration);
  v.duration_s = duration;
  nlohmann::json phases;
  files::ReadField(j, "", "phases", phases);
  if (!phases.is_array()) throw std::invalid_argument("phases: expected a list");
  for (size_t i = 0; i < phases.size(); ++i) {
    PhaseHold p;
    files::ReadFields(phases[i], "phases[" + std::to_string(i) + "]", p);
    v.phases.push_back(p);
  }
  files::ReadFields(j, "", v, AttemptFields{});
}

struct EpisodeMetricsFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("seed", v.seed);
    field("scene", v.scene);
    field("cell", v.cell);
    field("object_set", v.object_set);
    field("model", v.model);
    field("descriptor", v.descriptor);
    field("variation", v.variation);
    field("items", v.items);
    field("summary", v.summary);
    field("attempts", v.attempts);
    field("video", v.video);
  }
};
EpisodeMetricsFields RecordFieldsOf(const EpisodeMetrics*);

void to_json(nlohmann::json& j, const EpisodeMetrics& v) { files::WriteFields(j, v); }

}  // namespace sortcell::simcell
