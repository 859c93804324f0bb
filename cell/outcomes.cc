#include "cell/outcomes.h"

#include <stdexcept>
#include <utility>

namespace sortcell::cell {
namespace {

template <typename E, size_t N>
using Spellings = std::array<std::pair<E, const char*>, N>;

constexpr Spellings<AttemptResult, 6> kAttemptResults{{{AttemptResult::kReleased, "released"},
                                                       {AttemptResult::kMissed, "missed"},
                                                       {AttemptResult::kDropped, "dropped"},
                                                       {AttemptResult::kPutBack, "put_back"},
                                                       {AttemptResult::kMotionFailed, "motion_failed"},
                                                       {AttemptResult::kSimDiverged, "sim_diverged"}}};
constexpr Spellings<ItemOutcome, 8> kOutcomeNames{{{ItemOutcome::kSorted, "sorted"},
                                                   {ItemOutcome::kWrongBin, "wrong_bin"},
                                                   {ItemOutcome::kDropped, "dropped"},
                                                   {ItemOutcome::kGraspFailed, "grasp_failed"},
                                                   {ItemOutcome::kUnreachable, "unreachable"},
                                                   {ItemOutcome::kNotDetected, "not_detected"},
                                                   {ItemOutcome::kLeftOnTable, "left_on_table"},
                                                   {ItemOutcome::kUngraspable, "ungraspable"}}};
constexpr Spellings<EpisodeStatus, 4> kStatusNames{{{EpisodeStatus::kCompleted, "completed"},
                                                    {EpisodeStatus::kTimeLimit, "time_limit"},
                                                    {EpisodeStatus::kAttemptLimit, "attempt_limit"},
                                                    {EpisodeStatus::kSimDiverged, "sim_diverged"}}};

template <typename E, size_t N>
const char* Spell(const Spellings<E, N>& table, E value) {
  for (const auto& [v, text] : table) {
    if (v == value) return text;
  }
  return "?";  // Unreachable for a valid enumerator.
}

template <typename E, size_t N>
E Parse(const Spellings<E, N>& table, std::string_view text, const char* what) {
  std::string expected;
  for (const auto& [v, spelling] : table) {
    if (text == spelling) return v;
    expected += (expected.empty() ? "" : ", ") + std::string(spelling);
  }
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(text) + "' (expected " + expected +
                              ")");
}

}  // namespace

const char* ToString(AttemptResult result) { return Spell(kAttemptResults, result); }
const char* ToString(ItemOutcome outcome) { return Spell(kOutcomeNames, outcome); }
const char* ToString(EpisodeStatus status) { return Spell(kStatusNames, status); }

AttemptResult ParseAttemptResult(std::string_view text) { return Parse(kAttemptResults, text, "attempt result"); }
ItemOutcome ParseItemOutcome(std::string_view text) { return Parse(kOutcomeNames, text, "item outcome"); }
EpisodeStatus ParseEpisodeStatus(std::string_view text) { return Parse(kStatusNames, text, "episode status"); }

}  // namespace sortcell::cell
