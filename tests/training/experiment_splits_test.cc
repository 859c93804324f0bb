// How the experiments split a dataset (training/experiment_splits.h): the unseen-instance
// trials of Lai et al. 2011 hold out one instance of every category each, every instance once.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "training/experiment_splits.h"

namespace sortcell::training {
namespace {

// Labels only: `instances` per category, `views` samples each.
Dataset Labelled(const std::map<std::string, int>& instances, int views = 4) {
  Dataset d;
  d.views = views;
  for (const auto& [category, count] : instances) {
    for (int i = 1; i <= count; ++i) {
      for (int frame = 0; frame < views; ++frame) {
        Sample s;
        s.id = static_cast<int>(d.samples.size());
        s.category = category;
        s.instance = category + std::to_string(i);
        s.frame = frame;
        d.samples.push_back(s);
      }
    }
  }
  return d;
}

TEST(ExperimentSplits, EveryInstanceIsHeldOutOnceWithOnePerCategoryInEachTrial) {
  const Dataset d = Labelled({{"apple", 4}, {"lime", 2}, {"pear", 3}});
  const std::vector<Trial> trials = LeaveOneInstanceOutTrials(d, 0, 7);
  ASSERT_EQ(trials.size(), 4u);  // As many as the largest category has instances.
  std::map<std::string, int> times_held_out;
  for (const Trial& t : trials) {
    EXPECT_EQ(t.train.size() + t.test.size(), d.samples.size());
    std::set<std::string> tested, trained;
    std::map<std::string, std::set<std::string>> tested_per_category;
    for (int r : t.test) {
      tested.insert(d.samples[r].instance);
      tested_per_category[d.samples[r].category].insert(d.samples[r].instance);
    }
    for (int r : t.train) trained.insert(d.samples[r].instance);
    for (const auto& name : tested) EXPECT_EQ(trained.count(name), 0u) << name << " both trains and tests";
    EXPECT_EQ(tested_per_category.size(), 3u);
    for (const auto& [category, names] : tested_per_category) EXPECT_EQ(names.size(), 1u) << category;
    for (const auto& name : tested) ++times_held_out[name];
    EXPECT_EQ(t.request.group_by, Grouping::kInstance);
    EXPECT_EQ(t.description["test_instances"].size(), 3u);
  }
  EXPECT_EQ(times_held_out.size(), 9u);  // Every instance, the smaller categories' more than once.
  for (int i = 1; i <= 4; ++i) EXPECT_EQ(times_held_out["apple" + std::to_string(i)], 1);
  EXPECT_EQ(times_held_out["lime1"] + times_held_out["lime2"], 4);
}

TEST(ExperimentSplits, TheSameSeedHoldsOutTheSameInstances) {
  const Dataset d = Labelled({{"apple", 5}, {"lime", 5}});
  const auto a = LeaveOneInstanceOutTrials(d, 3, 11), b = LeaveOneInstanceOutTrials(d, 3, 11);
  ASSERT_EQ(a.size(), 3u);
  bool differs_for_another_seed = false;
  const auto c = LeaveOneInstanceOutTrials(d, 3, 12);
  for (size_t t = 0; t < a.size(); ++t) {
    EXPECT_EQ(a[t].test, b[t].test);
    differs_for_another_seed |= a[t].test != c[t].test;
  }
  EXPECT_TRUE(differs_for_another_seed);
}

TEST(ExperimentSplits, ACategoryWithOneInstanceIsNamed) {
  try {
    LeaveOneInstanceOutTrials(Labelled({{"apple", 3}, {"plate", 1}}), 0, 0);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("category 'plate' has one instance"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LeaveOneInstanceOutTrials(Labelled({{"apple", 3}}), -1, 0), std::invalid_argument);
}

TEST(ExperimentSplits, TheFrameSplitTestsEveryFourthView) {
  const Trial t = FrameSplit(Labelled({{"apple", 2}}, 8));
  EXPECT_EQ(t.test.size(), 4u);
  EXPECT_EQ(t.train.size(), 12u);
}

TEST(ExperimentSplits, TheSequenceSplitUsesApplesAndOrangesWhereThereAreAny) {
  const Trial paper = SequenceSplit(Labelled({{"apple", 2}, {"orange", 2}, {"lime", 2}}, 9), 0);
  EXPECT_EQ(paper.train.size() + paper.test.size(), 36u);  // No lime.
  const Trial other = SequenceSplit(Labelled({{"banana", 2}, {"lime", 2}}, 9), 0);
  EXPECT_EQ(other.train.size() + other.test.size(), 36u);
  EXPECT_EQ(other.request.label_kind, perception::LabelKind::kInstance);
}

}  // namespace
}  // namespace sortcell::training
