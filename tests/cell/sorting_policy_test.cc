// The sorting policy over a scripted cell, without a simulator: retries from fresh captures,
// unreachable clusters skipped and reported, the attempt and time budgets, a bin out of reach (the
// object is put back), fragments too small to describe never picked (unit).
#include "cell/sorting_policy.h"

#include <gtest/gtest.h>

#include <memory>

#include "cell/cell_layout.h"
#include "fake_cell.h"
#include "perception/descriptor.h"
#include "synthetic_scene.h"

namespace sortcell::cell {
namespace {

using sortcell_test::Cylinder;
using sortcell_test::FakeCell;

const Cylinder kBottle{{0.5, 0.1}, 0.03, 0.20, 40, 160, 60};  // green, tall: category "bottle"
const Cylinder kCup{{0.5, -0.1}, 0.04, 0.10, 220, 120, 30};   // orange, short: category "cup"

CellLayout Layout() {
  CellLayout layout;
  layout.p_W_bin["bottle"] = Eigen::Vector3d(0.15, 0.48, 0.008);
  layout.p_W_bin["cup"] = Eigen::Vector3d(0.45, 0.48, 0.008);
  return layout;
}

CameraCalibration Calibration() {
  CameraCalibration c;
  c.X_WC = sortcell_test::KinectPose();
  c.background = sortcell_test::RenderTable({}, c.X_WC);
  return c;
}

// A two-class model (bottle, cup) trained on the synthetic objects at a few table positions.
perception::RecognitionModel TrainModel() {
    const CameraCalibration calibration = Calibration();
    perception::SegmentationParams params;
    std::vector<Eigen::VectorXf> rows;
    std::vector<int> labels, groups;
    int group = 0;
    for (double x : {0.40, 0.45, 0.50, 0.55, 0.60}) {
      for (double y : {-0.15, 0.0, 0.15}) {
        for (int c = 0; c < 2; ++c) {
          Cylinder object = c == 0 ? kBottle : kCup;
          object.xy = {x, y};
          const auto cloud = sortcell_test::RenderTable({object}, calibration.X_WC);
          const auto segmented = perception::SegmentObjects(*cloud, calibration.X_WC, calibration.background.get(), params);
          if (segmented.segments.empty()) continue;
          const auto parts = perception::ComputeDescriptorParts(*segmented.segments[0].cloud_C);
          if (parts.status != perception::DescriptorStatus::kOk) continue;
          rows.push_back(perception::AssembleDescriptor(parts, perception::DescriptorKind::kColorCvfhNorm));
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

const perception::RecognitionModel& Model() {
  static const perception::RecognitionModel model = TrainModel();
  return model;
}

// Records what the policy reports.
struct Recorder : PolicyObserver {
  int observed = 0;
  std::vector<int> captures_before_attempt;  // Captures taken when each attempt started.
  std::vector<AttemptResult> results;
  std::vector<robot::GraspStatus> skipped;
  std::vector<std::optional<std::string>> categories;  // Of the last observation.
  const FakeCell* cell = nullptr;

  void Observed(const perception::Cloud&, const Observation& o, double) override {
    ++observed;
    categories.clear();
    for (const auto& d : o.detections) categories.push_back(d.category);
  }
  void Skipped(int, const Detection&, robot::GraspStatus why) override { skipped.push_back(why); }
  void AttemptStarting(const AttemptReport&) override { captures_before_attempt.push_back(cell->captures); }
  void AttemptEnded(const AttemptReport& r) override { results.push_back(r.pick.result); }
};

struct SortRun {
  PolicyResult result;
  Recorder seen;
  int captures = 0;
  std::vector<std::string> motions;
};

SortRun Sort(const std::vector<Cylinder>& objects, std::deque<bool> grasps, PolicyOptions options = {},
         CellLayout layout = Layout(), const perception::RecognitionModel& model = Model(), bool drop_on_lift = false) {
  const CameraCalibration calibration = Calibration();
  FakeCell cell(layout.q_observe);
  cell.clouds = {sortcell_test::RenderTable(objects, calibration.X_WC)};
  cell.grasps = std::move(grasps);
  cell.drop_on_lift = drop_on_lift;
  SortRun run;
  run.seen.cell = &cell;
  SortingPolicy policy(cell, layout, calibration, model, options, &run.seen);
  run.result = policy.Run();
  run.captures = cell.captures;
  run.motions = cell.motions;
  return run;
}

TEST(SortingPolicy, RecognisesTheSyntheticObjects) {
  const SortRun run = Sort({kBottle, kCup}, {}, [] {
    PolicyOptions o;
    o.max_attempts = 1;
    return o;
  }());
  ASSERT_EQ(run.seen.categories.size(), 2u);
  EXPECT_NE(run.seen.categories[0], run.seen.categories[1]);
  for (const auto& c : run.seen.categories) EXPECT_TRUE(c.has_value());
}

TEST(SortingPolicy, SortsAnObjectItHoldsAndMovesThroughThePhases) {
  // A scripted cell does not take the object away: after the release the same cloud is seen again,
  // so the next attempt at that position follows until the position is given up.
  const SortRun run = Sort({kBottle}, {true}, [] {
    PolicyOptions o;
    o.max_attempts = 1;
    return o;
  }());
  ASSERT_EQ(run.seen.results.size(), 1u);
  EXPECT_EQ(run.seen.results[0], AttemptResult::kReleased);
  EXPECT_EQ(run.result.status, EpisodeStatus::kAttemptLimit);
  const std::vector<std::string> expected{"approach", "descend", "reach", "lift", "carry", "lower", "retreat", "home"};
  EXPECT_EQ(run.motions, expected);
}

TEST(SortingPolicy, RetriesAMissedGraspFromAFreshCaptureUpToTheLimit) {
  PolicyOptions options;
  options.max_attempts_per_position = 3;
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
  layout.p_W_bin["bottle"] = Eigen::Vector3d(2.0, 2.0, 0.0);
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

TEST(SortingPolicy, NeverPicksAFragmentTooSmallToDescribe) {
  perception::RecognitionModel model = TrainModel();
  model.params.cvfh.min_points = 400;  // The small object below has fewer points after downsampling.
  const Cylinder fragment{{0.5, 0.0}, 0.02, 0.03, 40, 160, 60};
  const SortRun run = Sort({fragment}, {true}, {}, Layout(), model);
  ASSERT_EQ(run.seen.categories.size(), 1u);  // Seen ...
  EXPECT_FALSE(run.seen.categories[0].has_value());  // ... but not described ...
  EXPECT_TRUE(run.seen.results.empty());             // ... and never picked.
  EXPECT_TRUE(run.seen.skipped.empty());
  EXPECT_EQ(run.result.status, EpisodeStatus::kCompleted);
}

TEST(SortingPolicy, RejectsAModelClassWithoutABin) {
  CellLayout layout = Layout();
  layout.p_W_bin.erase("cup");
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
  EXPECT_THROW(SortingPolicy(cell, layout, calibration, Model(), options), std::invalid_argument);
  options = {};
  options.time_limit_s = 0;
  EXPECT_THROW(SortingPolicy(cell, layout, calibration, Model(), options), std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::cell
