#include "app/sweep/sweep_review.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "files/build_identity.h"
#include "files/json_fields.h"
#include "files/output_dir.h"
#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_replay.h"
#include "sim/ffmpeg_pipe.h"

namespace sortcell::app {
namespace {

constexpr double kSameClusterM = 0.05;  // A skipped cluster this near an item's final place was that item.

std::string Spaced(std::string text) {
  std::replace(text.begin(), text.end(), '_', ' ');
  return text;
}

// When the gripper, having held the object, first found itself empty: the end of that phase.
std::optional<simcell::PhaseHold> LostDuring(const simcell::AttemptLogEntry& a) {
  bool held = false;
  for (const auto& p : a.phases) {
    if (p.hold == "holding") held = true;
    if (held && p.hold == "empty") return p;
  }
  return std::nullopt;
}

std::string GraspInWords(const simcell::AttemptLogEntry& a) {
  for (const auto& p : a.phases) {
    if (p.phase != "grasp") continue;
    std::string text = fmt::format("closed at {:.0f} mm", 1000 * p.gap_m);
    if (a.width_m) text += fmt::format(" on a {:.0f} mm wide view", 1000 * *a.width_m);
    return text;
  }
  return "never closed";
}

std::string ResultInWords(const simcell::AttemptLogEntry& a) {
  if (a.result == "released") return "released over bin " + a.bin;
  if (a.result == "missed") return "closed on nothing";
  if (a.result == "dropped") {
    const auto lost = LostDuring(a);
    return lost ? fmt::format("dropped during {} at {:.1f} s", lost->phase, lost->end_s) : "dropped";
  }
  if (a.result == "put_back") return "put back: bin " + a.bin + " out of reach from here";
  if (a.result == "motion_failed") return "a motion failed" + (a.detail.empty() ? "" : ": " + a.detail);
  if (a.result == "sim_diverged") return "the simulation diverged";
  return Spaced(a.result);
}

double FailedAt(const simcell::AttemptLogEntry& a) {
  if (a.result == "dropped") {
    if (const auto lost = LostDuring(a)) return lost->end_s;
  }
  return a.time_s + a.duration_s.value_or(0);
}

bool NearItem(const simcell::AttemptLogEntry& a, const simcell::ItemResult& item) {
  return std::hypot(a.xy[0] - item.final_xyz[0], a.xy[1] - item.final_xyz[1]) < kSameClusterM;
}

// The last still taken at or before `at_s` (relative to `dir`), or "".
std::string StillBefore(const std::filesystem::path& dir, const std::filesystem::path& stills, double at_s) {
  std::string best;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir / stills, ec)) {
    const std::string name = entry.path().filename().string();
    long long ms = 0;
    if (std::sscanf(name.c_str(), "still_%lld.png", &ms) != 1 || ms > std::llround(1000 * at_s)) continue;
    if (name > best) best = name;  // Zero-padded: the latest sorts last.
  }
  return best.empty() ? "" : (stills / best).generic_string();
}

// A file name made of the item's name (letters, digits, '-', '_' and '.' kept; anything else '_').
std::string FileSafe(const std::string& name) {
  std::string safe = name;
  for (char& c : safe) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  return safe;
}

std::vector<simcell::AttemptLogEntry> AttemptsOf(const std::filesystem::path& metrics_file) {
  try {
    const auto metrics = nlohmann::json::parse(files::ReadTextFile(metrics_file));
    std::vector<simcell::AttemptLogEntry> attempts;
    const auto& list = metrics.at("attempts");
    for (size_t i = 0; i < list.size(); ++i) {
      try {
        attempts.push_back(list[i].get<simcell::AttemptLogEntry>());
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("attempts[" + std::to_string(i) + "]." + e.what());
      }
    }
    return attempts;
  } catch (const std::exception& e) {
    throw std::runtime_error("'" + metrics_file.string() + "': " + e.what());
  }
}

// Replays one episode with video and stills and adds its failures, each with its still and clip.
void ReviewEpisode(const std::filesystem::path& dir, const SweepRecord& record, const std::string& build,
                   double before_s, double after_s, SweepReview& review) {
  ReplayOptions options;
  options.sweep_dir = dir;
  options.episode = record.episode;
  const std::filesystem::path folder = fmt::format("replays/{:06d}", record.episode);
  std::filesystem::remove_all(dir / folder);  // No still or clip of an earlier replay may be taken for this one's.
  options.video = dir / folder / "episode.mp4";
  options.stills = dir / folder / "stills";
  const ReplayResult replay = ReplayRecord(record, options, build);
  ++review.episodes_replayed;
  if (!replay.matches)
    review.mismatches.push_back(fmt::format("episode {}: {}", record.episode, replay.differences.front()));
  const auto attempts = AttemptsOf(replay.out / "metrics.json");
  for (const auto& f : FailuresOf(record.items, attempts, record.summary.run.sim_time_s)) {
    // Never decided about: the cell's last look before it failed shows where it was left.
    const std::string still = StillBefore(dir, folder / "stills", f.decided_at_s.value_or(f.at_s));
    ReviewedFailure r{record.episode, record.seed, record.axes, f, "", still};
    const std::filesystem::path clip = folder / ("clip_" + FileSafe(f.item) + ".mp4");
    try {
      sim::CutVideo(options.video, dir / clip, std::max(0.0, f.at_s - before_s), before_s + after_s);
      r.clip = clip.generic_string();
    } catch (const std::runtime_error& e) {
      spdlog::warn("review: no clip of {} in episode {}: {}", f.item, record.episode, e.what());
    }
    review.failures.push_back(r);
  }
}

}  // namespace

std::string AttemptInWords(const simcell::AttemptLogEntry& a, int number) {
  const std::string called =
      a.category.empty() ? "not described"
                         : "called " + a.category + (a.confidence ? fmt::format(" ({:.2f})", *a.confidence) : "");
  if (!a.duration_s) {
    const std::string why = a.result.rfind("skipped: ", 0) == 0 ? a.result.substr(9) : a.result;
    return fmt::format("at {:.1f} s: seen, {}, not attempted: {}", a.time_s, called, Spaced(why));
  }
  std::string text =
      fmt::format("attempt {} at {:.1f}-{:.1f} s: {}{}; {}; {}", number, a.time_s, a.time_s + *a.duration_s, called,
                  a.bin.empty() ? "" : " for bin " + a.bin, GraspInWords(a), ResultInWords(a));
  if (a.squeezed_harder_in) text += "; squeezed harder during " + *a.squeezed_harder_in;
  return text;
}

std::vector<ItemFailure> FailuresOf(const std::vector<simcell::ItemResult>& items,
                                    const std::vector<simcell::AttemptLogEntry>& attempts, double episode_end_s) {
  std::vector<ItemFailure> failures;
  for (const auto& item : items) {
    if (item.outcome == cell::ItemOutcome::kSorted) continue;
    ItemFailure f;
    f.item = item.name;
    f.outcome = item.outcome;
    f.at_s = episode_end_s;
    int number = 0;
    const simcell::AttemptLogEntry* skipped = nullptr;
    for (const auto& a : attempts) {
      if (a.duration_s && a.truth_object == item.name) {
        f.log.push_back(AttemptInWords(a, ++number));
        f.at_s = FailedAt(a);
        f.decided_at_s = a.time_s;
      } else if (!a.duration_s && NearItem(a, item)) {
        skipped = &a;
      }
    }
    if (number == 0 && skipped) {
      f.log.push_back(AttemptInWords(*skipped, 0));
      f.at_s = skipped->time_s;
      f.decided_at_s = skipped->time_s;
    }
    if (f.log.empty()) f.log.push_back(fmt::format("never attempted; the episode ended at {:.1f} s", episode_end_s));
    failures.push_back(f);
  }
  return failures;
}

nlohmann::json ReviewJson(const SweepReview& review) {
  nlohmann::json failures = nlohmann::json::array();
  for (const auto& r : review.failures) {
    failures.push_back({{"episode", r.episode},
                        {"seed", r.seed},
                        {"axes", r.axes},
                        {"item", r.failure.item},
                        {"outcome", cell::ToString(r.failure.outcome)},
                        {"at_s", r.failure.at_s},
                        {"log", r.failure.log},
                        {"clip", r.clip},
                        {"still", r.still},
                        {"decided_at_s", files::OrNull(r.failure.decided_at_s)}});
  }
  return {{"episodes_replayed", review.episodes_replayed},
          {"mismatches", review.mismatches},
          {"not_replayed", review.not_replayed},
          {"failures", failures}};
}

SweepReview ReviewSweep(const std::filesystem::path& dir, double before_s, double after_s) {
  SweepReview review;
  const std::string build = files::BuildDigest();
  for (const auto& record : ReadSweepFolder(dir)) {
    const bool failed = std::any_of(record.items.begin(), record.items.end(), [](const simcell::ItemResult& i) {
      return i.outcome != cell::ItemOutcome::kSorted;
    });
    if (!record.ok() || !failed) continue;
    try {
      ReviewEpisode(dir, record, build, before_s, after_s, review);
    } catch (const std::exception& e) {  // One episode that cannot be replayed costs its own review only.
      const std::string episode = fmt::format("episode {}", record.episode), why = e.what();
      review.not_replayed.push_back(why.rfind(episode, 0) == 0 ? why : episode + ": " + why);
      spdlog::warn("review: {}", review.not_replayed.back());
    }
  }
  std::stable_sort(review.failures.begin(), review.failures.end(),
                   [](const ReviewedFailure& a, const ReviewedFailure& b) { return a.episode < b.episode; });
  files::WriteJson(dir / "review.json", ReviewJson(review));
  return review;
}

}  // namespace sortcell::app
