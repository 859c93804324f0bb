// Scoring an episode from ground truth, on a small inline cell (table, one bin, objects): every
// outcome, put-back objects not counted as dropped, the item tally and the summary, the typed
// metrics read back strictly, segment labelling and the outcome spellings (unit).
#include "simcell/episode_scoring.h"

#include <gtest/gtest.h>

#include "simcell/episode_metrics.h"
#include "simcell/segment_labels.h"
#include "simcell/sim_layout.h"
#include "error_of.h"
#include "sim/object_placement.h"

namespace sortcell::simcell {
namespace {

using sortcell_test::ErrorOf;

// A table top (x in [-0.3, 0.9], y in [-0.7, 0.7]), bin_cup at (0.45, 0.48), four small boxes.
const char* kCellXml = R"(
<mujoco>
  <worldbody>
    <geom name="table_top" type="plane" pos="0.3 0 0" size="0.6 0.7 0.01"/>
    <body name="bin_cup" pos="0.45 0.48 0">
      <site name="bin_cup" type="box" pos="0 0 0.008" size="0.1 0.1 0.001"/>
      <geom type="box" pos="0 0 0.004" size="0.108 0.108 0.004"/>
    </body>
    <body name="a" pos="0.5 0 0.03"><freejoint/><geom type="box" size="0.02 0.02 0.02"/></body>
    <body name="b" pos="0.6 0 0.03"><freejoint/><geom type="box" size="0.02 0.02 0.02"/></body>
    <body name="c" pos="0.7 0 0.03"><freejoint/><geom type="box" size="0.02 0.02 0.02"/></body>
    <body name="d" pos="0.4 0 0.03"><freejoint/><geom type="box" size="0.02 0.02 0.02"/></body>
  </worldbody>
</mujoco>)";

// The cell file of that scene: bin 'cup', 0.20 m square inside; cups to it, balls to 'ball'.
files::CellFile CupCell() {
  files::CellFile cell;
  cell.source = "cup cell";
  cell.bins.push_back({"cup", cell::Bin{Eigen::Vector3d(0.45, 0.48, 0.008), Eigen::Vector2d(0.1, 0.1)}});
  cell.rules.bin_of = {{"cup", "cup"}, {"ball", "ball"}};
  return cell;
}

class ScorerTest : public ::testing::Test {
 protected:
  void SetUp() override { mj_forward(model_.get(), data_.get()); }
  int Body(const std::string& name) const { return model_.Id(mjOBJ_BODY, name); }
  void Move(const std::string& name, double x, double y, double z) {
    const int adr = model_->jnt_qposadr[model_->body_jntadr[Body(name)]];
    data_->qpos[adr] = x, data_->qpos[adr + 1] = y, data_->qpos[adr + 2] = z;
    mj_forward(model_.get(), data_.get());
  }
  EpisodeScorer Scorer() const {
    const cell::CellLayout layout = ReadCellLayout(model_, CupCell());
    return EpisodeScorer({{"a", "cup", Body("a"), 1, "cup"},
                          {"b", "cup", Body("b"), 2, "cup"},
                          {"c", "ball", Body("c"), 3, "ball"},
                          {"d", "cup", Body("d"), 4, "cup"}},
                         4, {layout.table_min_xy, layout.table_max_xy});
  }
  // A 2x2 label image: pixel i shows object label i + 1.
  static cv::Mat Labels() { return (cv::Mat_<uint16_t>(2, 2) << 1, 2, 3, 4); }

  const sim::Model model_ = sim::Model::FromVirtualFiles({{"cell.xml", kCellXml}}, "inline cell");
  sim::Data data_{model_};
};

TEST_F(ScorerTest, ReadsTheLayoutFromTheCellFileAndTheTableFromTheScene) {
  const cell::CellLayout layout = ReadCellLayout(model_, CupCell());
  ASSERT_EQ(layout.bins.count("cup"), 1u);
  EXPECT_TRUE(layout.bins.at("cup").p_W_floor.isApprox(Eigen::Vector3d(0.45, 0.48, 0.008)));
  EXPECT_TRUE(layout.table_min_xy.isApprox(Eigen::Vector2d(-0.3, -0.7)));
  EXPECT_TRUE(layout.table_max_xy.isApprox(Eigen::Vector2d(0.9, 0.7)));
}

TEST(SimLayout, ASceneWithoutTableOrBinSiteOrWithOtherBinsIsNamed) {
  files::CellFile no_bins = CupCell();
  no_bins.bins.clear();
  const sim::Model no_table = sim::Model::FromVirtualFiles(
      {{"t.xml", "<mujoco><worldbody><geom name='floor' type='plane' size='1 1 0.1'/></worldbody></mujoco>"}},
      "no table");
  EXPECT_EQ(ErrorOf([&] { ReadCellLayout(no_table, no_bins); }), "scene 'no table': no table geom 'table_top'");
  const sim::Model no_site = sim::Model::FromVirtualFiles(
      {{"b.xml",
        "<mujoco><worldbody><body name='bin_cup'><geom type='box' size='0.1 0.1 0.01'/></body></worldbody></mujoco>"}},
      "no site");
  EXPECT_EQ(ErrorOf([&] { ReadCellLayout(no_site, CupCell()); }),
            "scene 'no site': bin 'bin_cup' has no box site 'bin_cup' (its floor centre, sized to its inside)");
  // The scene's bin stands elsewhere than the cell file's.
  const sim::Model moved = sim::Model::FromVirtualFiles({{"cell.xml", kCellXml}}, "inline cell");
  files::CellFile elsewhere = CupCell();
  elsewhere.bins[0].bin.p_W_floor.x() = 0.15;
  EXPECT_NE(ErrorOf([&] { ReadCellLayout(moved, elsewhere); }).find("bin 'cup' stands elsewhere"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { NominalCameraPose(no_site, "kinect"); }).find("kinect"), std::string::npos);
}

TEST_F(ScorerTest, EveryOutcomeFromWhereObjectsEndedAndWhatWasTried) {
  EpisodeScorer scorer = Scorer();
  const std::vector<int> p0{0}, p1{1}, p2{2};
  scorer.Observe(Labels(), {{&p0, std::string("cup"), 0.9}, {&p1, std::string("cup"), 0.8}, {&p2, std::nullopt, 0}});
  AttemptRecord sorted{scorer.ObjectOf(0), "cup", 0.9, 0, 10, true, true, cell::AttemptResult::kReleased};
  scorer.Attempt(sorted);
  AttemptRecord missed{scorer.ObjectOf(1), "cup", 0.8, 10, 15, false, false, cell::AttemptResult::kMissed};
  scorer.Attempt(missed);
  Move("a", 0.45, 0.48, 0.03);  // in its bin
  Move("c", 2.0, 0.0, 0.03);    // off the table
  const std::vector<ItemResult> items = scorer.Items(data_, sim::Bins(model_));
  ASSERT_EQ(items.size(), 4u);
  EXPECT_EQ(items[0].outcome, cell::ItemOutcome::kSorted);
  EXPECT_EQ(items[0].cycle_time_s, 10.0);
  EXPECT_EQ(items[1].outcome, cell::ItemOutcome::kGraspFailed);
  EXPECT_EQ(items[2].outcome, cell::ItemOutcome::kDropped);
  EXPECT_FALSE(items[2].predicted_category.has_value());
  EXPECT_EQ(items[3].outcome, cell::ItemOutcome::kNotDetected);
  EXPECT_EQ(scorer.attempts(), 2);
  EXPECT_EQ(scorer.grasps(), 1);
}

TEST_F(ScorerTest, WrongBinUnreachableAndLeftOnTable) {
  EpisodeScorer scorer = Scorer();
  const std::vector<int> p1{1}, p2{2}, p3{3};
  scorer.Observe(Labels(),
                 {{&p1, std::string("cup"), 0.9}, {&p2, std::string("cup"), 0.7}, {&p3, std::string("cup"), 0.6}});
  scorer.Unreachable(0);        // b: given up without a plan
  Move("c", 0.45, 0.48, 0.03);  // c (a ball) in the cup bin
  const std::vector<ItemResult> items = scorer.Items(data_, sim::Bins(model_));
  EXPECT_EQ(items[1].outcome, cell::ItemOutcome::kUnreachable);
  EXPECT_EQ(items[1].attempts, 0);
  EXPECT_EQ(items[2].outcome, cell::ItemOutcome::kWrongBin);
  EXPECT_EQ(items[3].outcome, cell::ItemOutcome::kLeftOnTable);
}

TEST_F(ScorerTest, AnObjectPutBackBecauseItsBinIsOutOfReachIsUnreachableNotDropped) {
  EpisodeScorer scorer = Scorer();
  const std::vector<int> p0{0};
  scorer.Observe(Labels(), {{&p0, std::string("cup"), 0.9}});
  scorer.Attempt({scorer.ObjectOf(0), "cup", 0.9, 0, 12, true, true, cell::AttemptResult::kPutBack});
  EXPECT_EQ(scorer.Items(data_, sim::Bins(model_))[0].outcome, cell::ItemOutcome::kUnreachable);
  // Lifted and then lost on the way, standing on the table: dropped.
  scorer.Attempt({scorer.ObjectOf(0), "cup", 0.9, 12, 20, true, true, cell::AttemptResult::kDropped});
  EXPECT_EQ(scorer.Items(data_, sim::Bins(model_))[0].outcome, cell::ItemOutcome::kDropped);
  // Then picked up again and put back: it stands on the table, its bin out of reach.
  scorer.Attempt({scorer.ObjectOf(0), "cup", 0.9, 20, 32, true, true, cell::AttemptResult::kPutBack});
  EXPECT_EQ(scorer.Items(data_, sim::Bins(model_))[0].outcome, cell::ItemOutcome::kUnreachable);
}

TEST(ItemTally, CountsOutcomesRecognitionAndCyclesOfItemsThatReachedABin) {
  std::vector<ItemResult> items(4);
  items[0].true_category = "cup", items[0].predicted_category = "cup", items[0].outcome = cell::ItemOutcome::kSorted,
  items[0].cycle_time_s = 10;
  items[1].true_category = "cup", items[1].predicted_category = "ball", items[1].outcome = cell::ItemOutcome::kWrongBin,
  items[1].cycle_time_s = 14;
  items[2].true_category = "ball", items[2].predicted_category = "ball", items[2].outcome = cell::ItemOutcome::kDropped,
  items[2].cycle_time_s = 30;
  items[3].true_category = "ball", items[3].outcome = cell::ItemOutcome::kNotDetected;
  RunFigures run;
  run.status = cell::EpisodeStatus::kTimeLimit;
  const EpisodeSummary s = SummarizeEpisode(items, 5, 3, run);
  EXPECT_EQ(s.items, 4);
  EXPECT_EQ(s.outcomes.at(cell::ItemOutcome::kSorted), 1);
  EXPECT_EQ(s.outcomes.at(cell::ItemOutcome::kLeftOnTable), 0);
  EXPECT_DOUBLE_EQ(*s.correct_sort_rate, 0.25);
  EXPECT_DOUBLE_EQ(*s.recognition_accuracy, 2.0 / 3);
  EXPECT_EQ(s.items_classified, 3);
  EXPECT_DOUBLE_EQ(*s.grasp_success_rate, 0.6);
  EXPECT_DOUBLE_EQ(*s.mean_cycle_time_s, 12.0);  // the dropped item's 30 s does not count
  EXPECT_FALSE(SummarizeEpisode({}, 0, 0, run).correct_sort_rate.has_value());
  EXPECT_FALSE(s.picks_per_hour.has_value());  // no simulated time
  run.sim_time_s = 90;
  EXPECT_DOUBLE_EQ(*SummarizeEpisode(items, 5, 3, run).picks_per_hour, 40.0);  // 1 sorted in 90 s
  EXPECT_FALSE(s.mean_cycle_bound_s.has_value());                              // no item with a bound
  EXPECT_FALSE(s.cycle_to_bound.has_value());
}

TEST(ItemTally, TheCycleBoundCountsOnlyItemsThatReachedABinWithABound) {
  std::vector<ItemResult> items(4);
  for (auto& item : items) item.true_category = "cup";
  items[0].outcome = cell::ItemOutcome::kSorted, items[0].cycle_time_s = 6, items[0].cycle_bound_s = 2;
  items[1].outcome = cell::ItemOutcome::kWrongBin, items[1].cycle_time_s = 9, items[1].cycle_bound_s = 4;
  items[2].outcome = cell::ItemOutcome::kDropped, items[2].cycle_time_s = 30, items[2].cycle_bound_s = 1;
  items[3].outcome = cell::ItemOutcome::kSorted, items[3].cycle_time_s = 12;  // an old record: no bound
  const EpisodeSummary s = SummarizeEpisode(items, 4, 4, RunFigures{});
  EXPECT_DOUBLE_EQ(*s.mean_cycle_time_s, 9.0);
  EXPECT_DOUBLE_EQ(*s.mean_cycle_bound_s, 3.0);
  EXPECT_DOUBLE_EQ(*s.cycle_to_bound, 15.0 / 6.0);  // the bounded items' cycles over their bounds
  const nlohmann::json written = s;
  EpisodeSummary back;
  from_json(written, back);
  EXPECT_DOUBLE_EQ(*back.mean_cycle_bound_s, 3.0);
  EXPECT_DOUBLE_EQ(*back.cycle_to_bound, 15.0 / 6.0);
}

TEST(EpisodeMetrics, ASummaryWrittenBeforeTheCycleFiguresStillReads) {
  RunFigures run;
  run.sim_time_s = 100;
  ItemResult item;
  item.outcome = cell::ItemOutcome::kSorted;
  nlohmann::json old = SummarizeEpisode({item}, 1, 1, run);
  for (const char* key : {"picks_per_hour", "cycle_phases_s", "tracking_max_error_rad", "torque_saturated_samples"}) {
    old.erase(key);
  }
  const EpisodeSummary s = old.get<EpisodeSummary>();
  EXPECT_DOUBLE_EQ(*s.picks_per_hour, 36.0);
  EXPECT_TRUE(s.run.cycle_phases_s.empty());
}

TEST(EpisodeMetrics, SummaryAndItemsReadBackAsWritten) {
  ItemResult item;
  item.name = "cup", item.true_category = "cup", item.predicted_category = "cup", item.attempts = 2;
  item.outcome = cell::ItemOutcome::kWrongBin, item.cycle_time_s = 11.5, item.final_xyz = {0.1, 0.2, 0.3};
  RunFigures run;
  run.status = cell::EpisodeStatus::kAttemptLimit, run.frames = 7, run.sim_time_s = 42;
  run.cycle_phases_s = {{"approach", 1.5}, {"carry", 2.25}};
  run.torque_saturated_samples = 3, run.tracking_max_error_rad = 0.01;
  const EpisodeSummary summary = SummarizeEpisode({item}, 3, 2, run);
  const ItemResult item_back = nlohmann::json(item).get<ItemResult>();
  EXPECT_EQ(nlohmann::json(item_back), nlohmann::json(item));
  const EpisodeSummary summary_back = nlohmann::json(summary).get<EpisodeSummary>();
  EXPECT_EQ(nlohmann::json(summary_back), nlohmann::json(summary));
  EXPECT_EQ(summary_back.run.status, cell::EpisodeStatus::kAttemptLimit);
  EXPECT_EQ(summary_back.run.cycle_phases_s, run.cycle_phases_s);
  EXPECT_EQ(summary_back.run.torque_saturated_samples, 3);
}

TEST(EpisodeMetrics, AMissingOrMistypedKeyIsAnErrorNamingIt) {
  nlohmann::json summary = SummarizeEpisode({}, 0, 0, {});
  summary.erase("grasps");
  EXPECT_EQ(ErrorOf([&] { summary.get<EpisodeSummary>(); }), "summary.grasps: missing");
  summary = SummarizeEpisode({}, 0, 0, {});
  summary["grasp_attempts"] = "three";
  EXPECT_EQ(ErrorOf([&] { summary.get<EpisodeSummary>(); }), "summary.grasp_attempts: expected a number, found string");
  summary = SummarizeEpisode({}, 0, 0, {});
  summary["grasps"] = 2.5;  // A count with a fraction is not read as 2.
  EXPECT_EQ(ErrorOf([&] { summary.get<EpisodeSummary>(); }), "summary.grasps: expected an integer, found 2.5");
  summary = SummarizeEpisode({}, 0, 0, {});
  summary["outcomes"].erase("dropped");
  EXPECT_EQ(ErrorOf([&] { summary.get<EpisodeSummary>(); }), "summary.outcomes.dropped: missing");
  nlohmann::json item = ItemResult{};
  item["outcome"] = "lost";
  EXPECT_NE(ErrorOf([&] { item.get<ItemResult>(); }).find("outcome: unknown item outcome 'lost' (expected sorted,"),
            std::string::npos);
}

TEST(Outcomes, EverySpellingReadsBack) {
  for (const auto o : cell::kItemOutcomes) EXPECT_EQ(cell::ParseItemOutcome(cell::ToString(o)), o);
  for (const auto s : {cell::EpisodeStatus::kCompleted, cell::EpisodeStatus::kTimeLimit,
                       cell::EpisodeStatus::kAttemptLimit, cell::EpisodeStatus::kSimDiverged}) {
    EXPECT_EQ(cell::ParseEpisodeStatus(cell::ToString(s)), s);
  }
  for (const auto r :
       {cell::AttemptResult::kReleased, cell::AttemptResult::kMissed, cell::AttemptResult::kDropped,
        cell::AttemptResult::kPutBack, cell::AttemptResult::kMotionFailed, cell::AttemptResult::kSimDiverged}) {
    EXPECT_EQ(cell::ParseAttemptResult(cell::ToString(r)), r);
  }
  EXPECT_EQ(ErrorOf([] { cell::ParseEpisodeStatus("done"); }),
            "unknown episode status 'done' (expected completed, time_limit, attempt_limit or sim_diverged)");
}

TEST(SegmentLabels, MajorityPurityAndIntersectionOverUnion) {
  const cv::Mat labels = (cv::Mat_<uint16_t>(2, 3) << 1, 1, 2, 1, 0, 2);
  const SegmentLabel l = LabelSegment(labels, {0, 1, 2}, 2);
  EXPECT_EQ(l.label, 1);
  EXPECT_DOUBLE_EQ(l.purity, 2.0 / 3);
  EXPECT_DOUBLE_EQ(l.iou, 2.0 / 4);  // 2 shared of {0, 1, 2, 3}
  EXPECT_EQ(LabelSegment(labels, {}, 2).label, 0);
}

TEST(SegmentLabels, RejectsLabelsAboveTheObjectCountAndPixelsOutside) {
  const cv::Mat labels = (cv::Mat_<uint16_t>(1, 3) << 1, 7, 2);
  EXPECT_EQ(ErrorOf([&] { LabelSegment(labels, {0, 1}, 2); }), "LabelSegment: label 7 exceeds the object count 2");
  EXPECT_EQ(ErrorOf([&] { LabelSegment(labels, {3}, 7); }), "LabelSegment: pixel 3 outside the 3x1 label image");
  EXPECT_EQ(ErrorOf([&] { LabelSegment(cv::Mat::zeros(1, 3, CV_8UC1), {0}, 7); }),
            "LabelSegment: the label image is not CV_16UC1");
}

}  // namespace
}  // namespace sortcell::simcell
