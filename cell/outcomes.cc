#include "cell/outcomes.h"

#include "common/enum_names.h"

namespace sortcell::cell {
namespace {

constexpr EnumNames<AttemptResult, 6> kAttemptResults{{{AttemptResult::kReleased, "released"},
                                                       {AttemptResult::kMissed, "missed"},
                                                       {AttemptResult::kDropped, "dropped"},
                                                       {AttemptResult::kPutBack, "put_back"},
                                                       {AttemptResult::kMotionFailed, "motion_failed"},
                                                       {AttemptResult::kSimDiverged, "sim_diverged"}}};
constexpr EnumNames<ItemOutcome, 8> kOutcomeNames{{{ItemOutcome::kSorted, "sorted"},
                                                   {ItemOutcome::kWrongBin, "wrong_bin"},
                                                   {ItemOutcome::kDropped, "dropped"},
                                                   {ItemOutcome::kGraspFailed, "grasp_failed"},
                                                   {ItemOutcome::kUnreachable, "unreachable"},
                                                   {ItemOutcome::kNotDetected, "not_detected"},
                                                   {ItemOutcome::kLeftOnTable, "left_on_table"},
                                                   {ItemOutcome::kUngraspable, "ungraspable"}}};
constexpr EnumNames<EpisodeStatus, 4> kStatusNames{{{EpisodeStatus::kCompleted, "completed"},
                                                    {EpisodeStatus::kTimeLimit, "time_limit"},
                                                    {EpisodeStatus::kAttemptLimit, "attempt_limit"},
                                                    {EpisodeStatus::kSimDiverged, "sim_diverged"}}};

}  // namespace

const char* ToString(AttemptResult result) { return NameOf(kAttemptResults, result); }
const char* ToString(ItemOutcome outcome) { return NameOf(kOutcomeNames, outcome); }
const char* ToString(EpisodeStatus status) { return NameOf(kStatusNames, status); }

AttemptResult ParseAttemptResult(std::string_view text) { return ParseName(kAttemptResults, text, "attempt result"); }
ItemOutcome ParseItemOutcome(std::string_view text) { return ParseName(kOutcomeNames, text, "item outcome"); }
EpisodeStatus ParseEpisodeStatus(std::string_view text) { return ParseName(kStatusNames, text, "episode status"); }

}  // namespace sortcell::cell
