// The sorting policy over a scripted cell, without a simulator: retries from fresh captures,
// unreachable clusters skipped and reported, the attempt and time budgets, a bin out of reach (the
// object is put back), fragments too small to describe never picked (unit).
#include "cell/sorting_policy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include "cell/cell_layout.h"
#include "error_of.h"
#include "fake_cell.h"
#include "perception/descriptor.h"
#include "perception/recognition_model.h"
#include "perception/segmentation.h"
#include "robot/ur5_kinematics.h"
#include "synthetic_scene.h"

namespace sortcell::cell {
namespace {

using sortcell_test::Cylinder;
using sortcell_test::FakeCell;

const Cylinder kBottle{{0.5, 0.1}, 0.03, 0.20, 40, 160, 60};  // green, tall: category "bottle"
const Cylinder kCup{{0.5, -0.1}, 0.04, 0.10, 220, 120, 30};   // orange, short: category "cup"

CellLayout Layout() {
  CellLayout layout;
  layout.bins["bottle"] = Bin{Eigen::Vector3d(0.15, 0.48, 0.008), Eigen::Vector2d(0.10, 0.10)};
  layout.bins["cup"] = Bin{Eigen::Vector3d(0.45, 0.48, 0.008), Eigen::Vector2d(0.10, 0.10)};
  layout.rules.bin_of = {{"bottle", "bottle"}, {"cup", "cup"}};
  return layout;
}

CameraCalibration Calibration() {
  CameraCalibration c;
  c.X_WC = sortcell_test::KinectPose();
  c.background = sortcell_test::RenderTable({}, c.X_WC);
  return c;
}

// The descriptor of one object alone on the table, as the cell sees it; none when nothing is segmented or
// the segment is too small to describe.
std::optional<perception::DescriptorParts> DescribeAlone(const Cylinder& object, const CameraCalibration& calibration) {
  const auto cloud = sortcell_test::RenderTable({object}, calibration.X_WC);
  const auto segmented = perception::SegmentObjects(*cloud, calibration.X_WC, calibration.background.get(), {});
  if (segmented.segments.empty()) return std::nullopt;
  auto parts = perception::ComputeDescriptorParts(*segmented.segments[0].cloud_C);
  if (parts.status != perception::DescriptorStatus::kOk) return std::nullopt;
  return parts;
}

// A two-class model (bottle, cup) trained on the synthetic objects at six table positions (few: run outside
// CTest every test process trains it again, and under the sanitizers a render and its descriptor take a
// third of a second).
perception::RecognitionModel TrainModel() {
  const CameraCalibration calibration = Calibration();
  std::vector<Eigen::VectorXf> rows;
  std::vector<int> labels, groups;
  int group = 0;
  for (double x : {0.40, 0.50, 0.60}) {
    for (double y : {-0.15, 0.15}) {
      for (int c = 0; c < 2; ++c) {
        Cylinder object = c == 0 ? kBottle : kCup;
        object.xy = {x, y};
        const auto parts = DescribeAlone(object, calibration);
        if (!parts) continue;
        rows.push_back(perception::AssembleDescriptor(*parts, perception::DescriptorKind::kColorCvfhNorm));
        labels.push_back(c);
        groups.push_back(group++ % 6);
      }
    }
  }
  Eigen::MatrixXf x(rows.size(), rows.empty() ? 0 : rows[0].size());
  for (size_t i = 0; i < rows.size(); ++i) x.row(i) = rows[i].transpose();
  perception::RecognitionModel m;
  m.descriptor = perception::DescriptorKind::kColorCvfhNorm;
  m.classes = {"bottle", "cup"};
  perception::SvmGrid grid;
  grid.C = {16};
  grid.gamma = {1.0 / 32};
  m.classifier = perception::SvmClassifier::Train(x, labels, groups, 2, grid);
  m.train_samples = static_cast<int>(rows.size());
  return m;
}

// Under CTest the model is trained once per run, by the fixture test below (sorting_policy_model,
// tests/CMakeLists.txt: it took about 4 s of each of some 20 test processes under the sanitizers) and read
// from the file it wrote; run by hand, each process trains its own.
constexpr const char* kSharedModelVariable = "SORTCELL_TEST_POLICY_MODEL";

const perception::RecognitionModel& Model() {
  static const perception::RecognitionModel model = [] {
    const char* shared = std::getenv(kSharedModelVariable);
    return shared ? perception::LoadModel(shared) : TrainModel();
  }();
  return model;
}

// The fixture: disabled, so that only the fixture's own command (--gtest_also_run_disabled_tests) runs it.
TEST(SortingPolicyModel, DISABLED_TrainedOnceForTheOtherTests) {
  const char* shared = std::getenv(kSharedModelVariable);
  ASSERT_NE(shared, nullptr) << kSharedModelVariable << " names the file to write";
  const perception::RecognitionModel trained = TrainModel();
  std::filesystem::create_directories(std::filesystem::path(shared).parent_path());
  perception::SaveModel(shared, trained);
  // What the other tests read classifies as the model they would have trained themselves.
  const perception::RecognitionModel read = perception::LoadModel(shared);
  ASSERT_EQ(read.classes, trained.classes);
  const auto parts = DescribeAlone(kCup, Calibration());
  ASSERT_TRUE(parts);
  EXPECT_EQ(read.Classify(*parts).name, "cup");
  EXPECT_EQ(read.Classify(*parts).probability, trained.Classify(*parts).probability);
}

// Records what the policy reports.
struct Recorder : PolicyObserver {
  int observed = 0;
  std::vector<int> captures_before_attempt;  // Captures taken when each attempt started.
  std::vector<AttemptResult> results;
  std::vector<robot::GraspStatus> skipped;
  std::vector<std::optional<std::string>> categories;  // Of the last observation.
  std::vector<Eigen::Vector2d> centres;                // Their footprint centres.
  std::vector<std::string> attempted;                  // Category of each attempt.
  const FakeCell* cell = nullptr;

  void Observed(const perception::Cloud&, const Observation& o, double) override {
    ++observed;
    categories.clear();
    centres.clear();
    for (const auto& d : o.detections) {
      categories.push_back(d.category);
      centres.push_back(d.footprint.centre_xy);
    }
  }
  void Skipped(int, const Detection&, robot::GraspStatus why) override { skipped.push_back(why); }
  void AttemptStarting(const AttemptReport& r) override {
    captures_before_attempt.push_back(cell->captures);
    attempted.push_back(r.seen->category.value_or("?"));
  }
  void AttemptEnded(const AttemptReport& r) override {
    results.push_back(r.pick.result);
    double phases = 0;
    for (const auto& p : r.phases) phases += p.end_s - p.start_s;
    phase_sums_match = phase_sums_match && std::abs(phases - (r.end_s - r.start_s)) < 1e-9 && !r.phases.empty();
    last_phases.clear();
    for (const auto& p : r.phases) last_phases.push_back(p.phase);
    squeezed_harder_in.push_back(r.pick.squeezed_harder_in);
    recentred_m.push_back(r.pick.recentred_m);
  }
  std::vector<double> recentred_m;              // Per attempt; 0 where the first grasp was centred.
  std::vector<std::string> squeezed_harder_in;  // Per attempt; empty where the grip held as it was.
  bool phase_sums_match = true;                 // Every attempt's phases add up to its duration.
  std::vector<std::string> last_phases;         // Of the last attempt.
};

struct SortRun {
  PolicyResult result;
  Recorder seen;
  int captures = 0;
  std::vector<std::string> motions;
  std::vector<robot::Joints> motion_ends;
};

SortRun Sort(const std::vector<Cylinder>& objects, std::deque<bool> grasps, PolicyOptions options = {},
             CellLayout layout = Layout(), const perception::RecognitionModel& model = Model(),
             bool drop_on_lift = false, const std::string& fault_on = "", bool slip_on_carry = false) {
  const CameraCalibration calibration = Calibration();
  FakeCell cell(layout.q_observe);
  cell.clouds = {sortcell_test::RenderTable(objects, calibration.X_WC)};
  cell.grasps = std::move(grasps);
  cell.drop_on_lift = drop_on_lift;
  cell.fault_on = fault_on;
  cell.slip_on_carry = slip_on_carry;
  SortRun run;
  run.seen.cell = &cell;
  SortingPolicy policy(cell, layout, calibration, model, options, &run.seen);
  run.result = policy.Run();
  run.captures = cell.captures;
  run.motions = cell.motions;
  run.motion_ends = cell.motion_ends;
  return run;
}

TEST(SortingPolicy, RecognisesTheSyntheticObjects) {
  const SortRun run = Sort({kBottle, kCup}, {}, [] {
    PolicyOptions o;
    o.max_attempts = 1;
    return o;
  }());
  ASSERT_EQ(run.seen.categories.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    // Each cluster named for the object standing where its footprint is.
    const bool bottle = (run.seen.centres[i] - kBottle.xy).norm() < (run.seen.centres[i] - kCup.xy).norm();
    EXPECT_EQ(run.seen.categories[i], std::optional<std::string>(bottle ? "bottle" : "cup"));
    EXPECT_LT((run.seen.centres[i] - (bottle ? kBottle.xy : kCup.xy)).norm(), 0.01);
  }
}

TEST(SortingPolicy, SortsAnObjectItHoldsAndMovesThroughThePhases) {
  const SortRun run = Sort({kBottle}, {true}, [] {
    PolicyOptions o;
    o.max_attempts = 1;
    return o;
  }());
  ASSERT_EQ(run.seen.results.size(), 1u);
  EXPECT_EQ(run.seen.results[0], AttemptResult::kReleased);
  EXPECT_EQ(run.result.status, EpisodeStatus::kAttemptLimit);
  // The next view is captured during the carry, where the arm leaves the camera's view (the second
  // capture). The arm stays in the bin after the release and goes home, straight up first, when the
  // episode ends.
  const std::vector<std::string> expected{"approach", "descend", "reach",   "lift", "carry",
                                          "lower",    "place",   "retreat", "home"};
  EXPECT_EQ(run.motions, expected);
  EXPECT_EQ(run.captures, 2);
  // The attempt's phases, gripper ones included, account for all of its time.
  EXPECT_TRUE(run.seen.phase_sums_match);
  EXPECT_EQ(run.seen.last_phases, (std::vector<std::string>{"approach", "descend", "reach", "grasp", "lift", "carry",
                                                            "carry", "lower", "place", "release"}));
}

// Where each of the run's motions of `phase` left the TCP, in order.
std::vector<Eigen::Vector3d> TcpPositionsAfter(const SortRun& run, const std::string& phase) {
  std::vector<Eigen::Vector3d> p;
  for (size_t i = 0; i < run.motions.size(); ++i) {
    if (run.motions[i] == phase) p.push_back(robot::TcpPose(run.motion_ends[i]).translation());
  }
  return p;
}

// The TCP's height where each of the run's motions of `phase` left the arm, in order.
std::vector<double> TcpZsAfter(const SortRun& run, const std::string& phase) {
  std::vector<double> z;
  for (const Eigen::Vector3d& p : TcpPositionsAfter(run, phase)) z.push_back(p.z());
  return z;
}

// Where the run let go of each object: the TCP's xy at the end of each lowering into a bin.
std::vector<Eigen::Vector2d> ReleasePoints(const SortRun& run) {
  std::vector<Eigen::Vector2d> released;
  for (const Eigen::Vector3d& p : TcpPositionsAfter(run, "lower")) released.push_back(p.head<2>());
  return released;
}

TEST(SortingPolicy, ReleasesIntoThePredictedBinSlotBySlot) {
  // The scripted cell does not take the object away: it is seen and sorted again, into the next slot.
  PolicyOptions options;
  options.max_attempts = 2;
  const SortRun run = Sort({kBottle}, {true, true}, options);
  ASSERT_EQ(run.seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased, AttemptResult::kReleased}));
  const std::vector<Eigen::Vector2d> released = ReleasePoints(run);
  const CellLayout layout = Layout();
  ASSERT_EQ(released.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT((released[k] - BinSlot(layout, "bottle", k).head<2>()).norm(), 1e-4) << k;
  }
}

TEST(SortingPolicy, ATallObjectGoesToASlotTheArmCanLetItGoIn) {
  // The bottle's bin where the default cell has its cup bin: its (+x, +y) corner slot, the second in
  // the layout's order, is out of reach for an object held as high above its bottom as the bottle
  // (the arm reaches down there only for objects held up to 0.10 m above their bottom). The scripted
  // cell does not take the bottle away, so it is sorted twice: the second time into another slot,
  // not put back.
  CellLayout layout = Layout();
  layout.bins["bottle"] = Bin{Eigen::Vector3d(0.45, 0.50, 0.008), Eigen::Vector2d(0.13, 0.13)};
  layout.bins["cup"] = Bin{Eigen::Vector3d(0.15, 0.50, 0.008), Eigen::Vector2d(0.13, 0.13)};
  PolicyOptions options;
  options.max_attempts = 2;
  const SortRun run = Sort({kBottle}, {true, true}, options, layout);
  ASSERT_EQ(run.seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased, AttemptResult::kReleased}));
  const std::vector<Eigen::Vector2d> released = ReleasePoints(run);
  ASSERT_EQ(released.size(), 2u);
  EXPECT_LT((released[0] - BinSlot(layout, "bottle", 0).head<2>()).norm(), 1e-4);
  // Not the out-of-reach slot 1: the next in the layout's order, slot 2, the (-x, +y) corner.
  EXPECT_LT((released[1] - BinSlot(layout, "bottle", 2).head<2>()).norm(), 1e-4);
}

TEST(SortingPolicy, AnObjectSeenInTheBinIsNotLetGoOnto) {
  // Something already stands in the bottle bin's first slot (the camera sees into the bins): the
  // release goes to the next slot. The scripted cell never shows what was released, so the camera
  // sees that slot empty again and the second release goes there too, never onto the first slot.
  const CellLayout layout = Layout();
  const Eigen::Vector3d p_slot0 = BinSlot(layout, "bottle", 0);
  const Cylinder in_bin{p_slot0.head<2>(), 0.03, 0.15, 200, 200, 200};
  PolicyOptions options;
  options.max_attempts = 2;
  const SortRun run = Sort({kBottle, in_bin}, {true, true}, options);
  ASSERT_EQ(run.seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased, AttemptResult::kReleased}));
  const std::vector<Eigen::Vector2d> released = ReleasePoints(run);
  ASSERT_EQ(released.size(), 2u);
  EXPECT_LT((released[0] - BinSlot(layout, "bottle", 1).head<2>()).norm(), 1e-4);
  EXPECT_LT((released[1] - BinSlot(layout, "bottle", 1).head<2>()).norm(), 1e-4);
}

// How high the held object's bottom was lifted above where it stood: the TCP at the lift's end over
// its height at the grasp (the reach's end), in the run's first attempt.
double FirstLift(const SortRun& run) {
  double grasp_z = 0;
  for (size_t i = 0; i < run.motions.size(); ++i) {
    if (run.motions[i] == "reach") grasp_z = robot::TcpPose(run.motion_ends[i]).translation().z();
    if (run.motions[i] == "lift") return robot::TcpPose(run.motion_ends[i]).translation().z() - grasp_z;
  }
  return 0;
}

// The TCP's height where the run's first motion of `phase` left the arm; NaN if none.
double TcpZAfter(const SortRun& run, const std::string& phase) {
  const std::vector<double> z = TcpZsAfter(run, phase);
  return z.empty() ? std::nan("") : z.front();
}

// The TCP's height where the run's last motion of `phase` left the arm; NaN if none.
double TcpZAfterLast(const SortRun& run, const std::string& phase) {
  const std::vector<double> z = TcpZsAfter(run, phase);
  return z.empty() ? std::nan("") : z.back();
}

TEST(SortingPolicy, LiftsOnlyAsHighAsWhatTheCarryPassesOverNeeds) {
  PolicyOptions options;
  options.max_attempts = 1;
  // (The fake cell records the lift's end in the middle of its blend into the carry: a few mm low.)
  // The cup alone: lifted only as high as its bin's walls need (0.10 m; it passes 3 cm over them), not
  // the 0.30 m a lift that sees nothing would need.
  const CellLayout layout = Layout();
  const robot::GraspOptions grasping;
  const SortRun alone = Sort({kCup}, {true}, options);
  ASSERT_EQ(alone.seen.results, std::vector<AttemptResult>{AttemptResult::kReleased});
  EXPECT_GE(FirstLift(alone), layout.bin_wall_height + 0.03 - 0.005);
  EXPECT_LT(FirstLift(alone), 0.20);
  // The open fingers came over to it low too: the approach ended (in its blend into the descent) less
  // than 5 cm above the pre-grasp pose (its via pose 3 cm above it, nothing being in the way), not at
  // the grasp plan's lift.
  EXPECT_LT(TcpZAfter(alone, "approach") - TcpZAfter(alone, "descend"), 0.05);
  // Home at the end goes straight up out of the bin as high as before first (the joint move home is
  // checked against nothing): the held object's bottom would be 0.30 m over the floor, far above the
  // 5 cm over the release point where the lowering ended.
  EXPECT_GT(TcpZAfterLast(alone, "retreat") - TcpZAfterLast(alone, "lower"), 0.15);
  // Something 0.20 m tall stands in a corner of the cup's bin, clear of the slot the cup goes to (the
  // camera sees it): the carry comes over the bin, so the cup goes high enough for its bottom to pass
  // 3 cm above it, still lower than a lift that sees nothing.
  const Cylinder tall{BinSlot(layout, "cup", 3).head<2>(), 0.03, 0.20, 200, 200, 200};
  const SortRun over_tall = Sort({kCup, tall}, {true}, options);
  ASSERT_EQ(over_tall.seen.results, std::vector<AttemptResult>{AttemptResult::kReleased});
  EXPECT_GT(FirstLift(over_tall), 0.20 + 0.02);
  EXPECT_LT(FirstLift(over_tall), grasping.lift_clearance - 0.005);
  // 0.28 m tall: a carry 3 cm over it would have to go higher than a lift that sees nothing, so the cup
  // goes as high as that lift, as before.
  const Cylinder taller{BinSlot(layout, "cup", 3).head<2>(), 0.03, 0.28, 200, 200, 200};
  const SortRun over_taller = Sort({kCup, taller}, {true}, options);
  ASSERT_EQ(over_taller.seen.results, std::vector<AttemptResult>{AttemptResult::kReleased});
  EXPECT_NEAR(FirstLift(over_taller), grasping.lift_clearance, 0.01);
}

TEST(SortingPolicy, AnApproachThatCannotPassLowComesOverViaTheGraspPlansLift) {
  // The scripted cell does not take the cup away: it is sorted twice, the second approach coming from
  // the cup's bin. Nothing in the way: the approach ends less than 5 cm above the pre-grasp (where the
  // descent starts).
  PolicyOptions options;
  options.max_attempts = 2;
  const SortRun open = Sort({kCup}, {true, true}, options);
  ASSERT_EQ(open.seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased, AttemptResult::kReleased}));
  ASSERT_EQ(TcpZsAfter(open, "approach").size(), 2u);
  EXPECT_LT(TcpZsAfter(open, "approach")[1] - TcpZsAfter(open, "descend")[1], 0.05);
  // A 0.38 m column stands in the bin's next slot (the camera sees it; the cup goes to the slot beside
  // it): no way from the bin below the grasp plan's lift passes 3 cm over it, so the arm comes over to
  // the cup via the plan's lift, as before the carry and approach were checked against the scene.
  const CellLayout layout = Layout();
  const Cylinder column{BinSlot(layout, "cup", 1).head<2>(), 0.03, 0.38, 200, 200, 200};
  const SortRun blocked = Sort({kCup, column}, {true, true}, options);
  ASSERT_EQ(blocked.seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased, AttemptResult::kReleased}));
  const std::vector<double> approach = TcpZsAfter(blocked, "approach"), descend = TcpZsAfter(blocked, "descend");
  ASSERT_EQ(approach.size(), 2u);
  ASSERT_EQ(descend.size(), 2u);
  EXPECT_GT(approach[1] - descend[1], 0.15) << "the approach came over at the grasp plan's lift";
}

TEST(SortingPolicy, ACarryIntoARaisedBinArrivesNoLowerThanWhereTheSlowPlacingStarts) {
  // The cup's bin stands on a 5 cm shelf with 2 cm walls: a carry as low as what it passes over would
  // arrive below where the lowering ends (5 cm over the release point, where the slow placing starts).
  // It arrives above it, so the lowering goes down.
  CellLayout layout = Layout();
  layout.bins["cup"].p_W_floor.z() = 0.05;
  layout.bin_wall_height = 0.02;
  PolicyOptions options;
  options.max_attempts = 1;
  const SortRun run = Sort({kCup}, {true}, options, layout);
  ASSERT_EQ(run.seen.results, std::vector<AttemptResult>{AttemptResult::kReleased});
  EXPECT_GT(TcpZAfter(run, "carry"), TcpZAfter(run, "lower"));
}

TEST(SortingPolicy, AFaultOfTheCellEndsTheEpisode) {
  const SortRun run = Sort({kBottle}, {true}, {}, Layout(), Model(), false, "carry");
  ASSERT_EQ(run.seen.results.size(), 1u);
  EXPECT_EQ(run.seen.results[0], AttemptResult::kSimDiverged);
  EXPECT_EQ(run.result.status, EpisodeStatus::kSimDiverged);
  EXPECT_EQ(run.motions.back(), "carry");  // Nothing moves after the fault.
}

TEST(SortingPolicy, RetriesAMissedGraspFromAFreshCaptureUpToTheLimit) {
  PolicyOptions options;
  options.pick.max_attempts_per_position = 3;
  const SortRun run = Sort({kBottle}, {false, false, false, false}, options);
  ASSERT_EQ(run.seen.results.size(), 3u);
  for (const auto r : run.seen.results) EXPECT_EQ(r, AttemptResult::kMissed);
  // Each attempt starts from a capture of its own; a fourth capture finds the position given up.
  EXPECT_EQ(run.seen.captures_before_attempt, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(run.captures, 4);
  EXPECT_EQ(run.result.attempts, 3);
  EXPECT_EQ(run.result.status, EpisodeStatus::kCompleted);
}

TEST(SortingPolicy, SkipsAndReportsAnUnreachableCluster) {
  Cylinder far = kBottle;
  far.xy = {0.86, 0.0};  // On the table and in view, beyond the arm's reach for a top-down grasp.
  const SortRun run = Sort({far}, {true});
  ASSERT_EQ(run.seen.skipped.size(), 1u);
  EXPECT_EQ(run.seen.skipped[0], robot::GraspStatus::kUnreachable);
  EXPECT_TRUE(run.seen.results.empty());
  EXPECT_EQ(run.result.attempts, 0);
  EXPECT_EQ(run.result.status, EpisodeStatus::kCompleted);
}

TEST(SortingPolicy, TheAttemptBudgetEndsTheEpisode) {
  Cylinder other = kCup;
  PolicyOptions options;
  options.max_attempts = 2;
  const SortRun run = Sort({kBottle, other}, {false, false, false, false, false, false}, options);
  EXPECT_EQ(run.result.attempts, 2);
  EXPECT_EQ(run.result.status, EpisodeStatus::kAttemptLimit);
}

TEST(SortingPolicy, TheTimeBudgetEndsTheEpisode) {
  PolicyOptions options;
  options.time_limit_s = 1.0;  // One attempt takes longer.
  const SortRun run = Sort({kBottle}, {false, false, false}, options);
  EXPECT_EQ(run.result.attempts, 1);
  EXPECT_EQ(run.result.status, EpisodeStatus::kTimeLimit);
}

TEST(SortingPolicy, PutsBackAnObjectWhoseBinIsOutOfReachWithoutCountingItDropped) {
  CellLayout layout = Layout();
  layout.bins["bottle"].p_W_floor = Eigen::Vector3d(2.0, 2.0, 0.0);
  const SortRun run = Sort({kBottle}, {true, true}, {}, layout);
  ASSERT_EQ(run.seen.results.size(), 1u);  // Given up as unreachable afterwards: no second attempt.
  EXPECT_EQ(run.seen.results[0], AttemptResult::kPutBack);
  EXPECT_EQ(run.result.status, EpisodeStatus::kCompleted);
  const std::vector<std::string> expected{"approach", "descend", "reach", "lift", "put_back", "retreat", "home"};
  EXPECT_EQ(run.motions, expected);
}

TEST(SortingPolicy, ReportsADropDuringTheLift) {
  PolicyOptions options;
  options.max_attempts = 1;
  const SortRun run = Sort({kBottle}, {true}, options, Layout(), Model(), /*drop_on_lift=*/true);
  ASSERT_EQ(run.seen.results.size(), 1u);
  EXPECT_EQ(run.seen.results[0], AttemptResult::kDropped);
}

TEST(SortingPolicy, ASlipDuringTheCarryIsCaughtBySqueezingHarder) {
  // The scripted object slips from the carry's start and is lost within 60 ms unless squeezed
  // harder: the pads' shear says so, the fingers firm up, and it reaches its bin.
  PolicyOptions options;
  options.max_attempts = 1;
  const SortRun run = Sort({kBottle}, {true}, options, Layout(), Model(), false, "", /*slip_on_carry=*/true);
  ASSERT_EQ(run.seen.results.size(), 1u);
  EXPECT_EQ(run.seen.results[0], AttemptResult::kReleased);
  EXPECT_EQ(run.seen.squeezed_harder_in, (std::vector<std::string>{"carry"}));
  // A grip that holds as it is is left alone.
  const SortRun calm = Sort({kBottle}, {true}, options);
  EXPECT_EQ(calm.seen.squeezed_harder_in, (std::vector<std::string>{""}));
}

TEST(SortingPolicy, AGraspThatClosedOffCentreIsMadeAgainOverTheObject) {
  // The first closing finds the object 12 mm off the TCP's axis (the left finger 12 mm farther out
  // than the right): the fingers open, the TCP moves 12 mm along its y over the object, and they
  // close again, centred, before the lift.
  const CameraCalibration calibration = Calibration();
  const CellLayout layout = Layout();  // The policy keeps references to these.
  const perception::RecognitionModel& model = Model();
  FakeCell cell(layout.q_observe);
  cell.clouds = {sortcell_test::RenderTable({kBottle}, calibration.X_WC)};
  cell.grasps = {true, true};
  cell.grasp_offsets = {0.012, 0.0};
  Recorder seen;
  seen.cell = &cell;
  PolicyOptions options;
  options.max_attempts = 1;
  SortingPolicy policy(cell, layout, calibration, model, options, &seen);
  policy.Run();
  ASSERT_EQ(seen.results, (std::vector<AttemptResult>{AttemptResult::kReleased}));
  ASSERT_EQ(seen.recentred_m.size(), 1u);
  EXPECT_DOUBLE_EQ(seen.recentred_m[0], 0.012);
  const auto at = [&](const std::string& phase) {
    const size_t i = std::find(cell.motions.begin(), cell.motions.end(), phase) - cell.motions.begin();
    EXPECT_LT(i, cell.motions.size()) << phase;
    return robot::TcpPose(cell.motion_ends.at(i));
  };
  const Eigen::Isometry3d X_WT_reach = at("reach"), X_WT_recentre = at("recentre");
  const Eigen::Vector3d moved_T =
      X_WT_reach.linear().transpose() * (X_WT_recentre.translation() - X_WT_reach.translation());
  EXPECT_LT((moved_T - Eigen::Vector3d(0, 0.012, 0)).norm(), 1e-4) << moved_T.transpose();
  // A centred grasp is left as it is.
  const SortRun calm = Sort({kBottle}, {true}, options);
  EXPECT_EQ(calm.seen.recentred_m, (std::vector<double>{0.0}));
  EXPECT_EQ(std::count(calm.motions.begin(), calm.motions.end(), "recentre"), 0);
}

TEST(SortingPolicy, NeverPicksAFragmentTooSmallToDescribe) {
  perception::RecognitionModel model = TrainModel();
  model.params.cvfh.min_points = 400;  // The small object below has fewer points after downsampling.
  const Cylinder fragment{{0.45, -0.12}, 0.02, 0.03, 40, 160, 60};
  PolicyOptions options;
  options.pick.max_attempts_per_position = 1;
  const SortRun run = Sort({fragment, kBottle}, {false}, options, Layout(), model);
  // Both seen; the fragment not described; only the bottle attempted (once), then nothing left.
  ASSERT_EQ(run.seen.categories.size(), 2u);
  int undescribed = 0;
  for (const auto& c : run.seen.categories) undescribed += c.has_value() ? 0 : 1;
  EXPECT_EQ(undescribed, 1);
  EXPECT_EQ(run.seen.attempted, (std::vector<std::string>{"bottle"}));
  EXPECT_TRUE(run.seen.skipped.empty());
  EXPECT_EQ(run.result.status, EpisodeStatus::kCompleted);
}

TEST(SortingPolicy, RejectsAModelClassWithoutABin) {
  CellLayout layout = Layout();
  layout.rules.bin_of.erase("cup");
  FakeCell cell(layout.q_observe);
  const CameraCalibration calibration = Calibration();
  try {
    SortingPolicy policy(cell, layout, calibration, Model(), {});
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'cup'"), std::string::npos) << e.what();
  }
}

TEST(SortingPolicy, RejectsBudgetsOutOfRange) {
  const CellLayout layout = Layout();
  FakeCell cell(layout.q_observe);
  const CameraCalibration calibration = Calibration();
  PolicyOptions options;
  options.max_attempts = 0;
  const auto error = [&] {
    return sortcell_test::ErrorOf([&] { SortingPolicy(cell, layout, calibration, Model(), options); });
  };
  EXPECT_EQ(error(), "policy options: attempt limits must be at least 1");
  options = {};
  options.pick.max_attempts_per_position = 0;
  EXPECT_EQ(error(), "policy options: attempt limits must be at least 1");
  options = {};
  options.time_limit_s = 0;
  EXPECT_EQ(error(), "policy options: time limit must be > 0 s");
}

TEST(CellLayout, BinSlotsCycleAndAnUnknownBinIsNamed) {
  const CellLayout layout = Layout();
  const Eigen::Vector3d p_W_cup = layout.bins.at("cup").p_W_floor;
  EXPECT_TRUE(BinSlot(layout, "cup", 0).isApprox(p_W_cup + Eigen::Vector3d(-0.05, -0.05, 0)));
  EXPECT_TRUE(BinSlot(layout, "cup", 6).isApprox(p_W_cup + Eigen::Vector3d(0.05, 0.05, 0)));
  EXPECT_EQ(sortcell_test::ErrorOf([&] { BinSlot(layout, "plate", 0); }), "cell layout: no bin 'plate'");
}

TEST(ObserveScene, MisuseThrowsAndAnEmptyViewIsAStatus) {
  const CameraCalibration calibration = Calibration();
  perception::Cloud unorganized = *sortcell_test::RenderTable({kBottle}, calibration.X_WC);
  unorganized.width = unorganized.width * unorganized.height;
  unorganized.height = 1;
  EXPECT_NE(sortcell_test::ErrorOf([&] { ObserveScene(unorganized, calibration, {}, Model()); }).find("not organized"),
            std::string::npos);
  // The camera turned away from the table: nothing valid in view, a status, not an exception.
  CameraCalibration away = calibration;
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.translation() = Eigen::Vector3d(0.5, 0, 0.75);  // looking straight up
  const auto sky = sortcell_test::RenderTable({}, X_WC);
  away.background = nullptr;
  const Observation o = ObserveScene(*sky, away, {}, Model());
  EXPECT_EQ(o.status, perception::SegmentationStatus::kNoValidPoints);
  EXPECT_TRUE(o.detections.empty());
}

}  // namespace
}  // namespace sortcell::cell
