// Metrics against values computed by hand from small confusion matrices.
#include "perception/metrics.h"

#include <gtest/gtest.h>

namespace sortcell::perception {
namespace {

TEST(Metrics, MatchHandComputedThreeClassExample) {
  // rows actual, columns predicted
  //          a  b  c
  //   a      5  1  0
  //   b      2  3  1
  //   c      0  0  4
  ConfusionMatrix m({"a", "b", "c"});
  m.Add(0, 0, 5);
  m.Add(0, 1, 1);
  m.Add(1, 0, 2);
  m.Add(1, 1, 3);
  m.Add(1, 2, 1);
  m.Add(2, 2, 4);
  const RecognitionMetrics r = ComputeMetrics(m);
  // a: TP 5, FN 1, FP 2, TN 8 -> recall 5/6, precision 5/7, accuracy 13/16, F1 = 2*5/(2*5+1+2) = 10/13.
  EXPECT_EQ(r.per_class[0].tp, 5);
  EXPECT_EQ(r.per_class[0].tn, 8);
  EXPECT_DOUBLE_EQ(r.per_class[0].recall, 5.0 / 6);
  EXPECT_DOUBLE_EQ(r.per_class[0].precision, 5.0 / 7);
  EXPECT_DOUBLE_EQ(r.per_class[0].accuracy, 13.0 / 16);
  EXPECT_NEAR(r.per_class[0].f1, 10.0 / 13, 1e-12);
  // b: TP 3, FN 3, FP 1, TN 9 -> recall 1/2, precision 3/4, accuracy 12/16, F1 6/10.
  EXPECT_DOUBLE_EQ(r.per_class[1].recall, 0.5);
  EXPECT_DOUBLE_EQ(r.per_class[1].precision, 0.75);
  EXPECT_DOUBLE_EQ(r.per_class[1].accuracy, 0.75);
  EXPECT_NEAR(r.per_class[1].f1, 0.6, 1e-12);
  // c: TP 4, FN 0, FP 1, TN 11 -> recall 1, precision 4/5, accuracy 15/16, F1 8/9.
  EXPECT_DOUBLE_EQ(r.per_class[2].recall, 1.0);
  EXPECT_DOUBLE_EQ(r.per_class[2].precision, 0.8);
  EXPECT_NEAR(r.per_class[2].f1, 8.0 / 9, 1e-12);
  EXPECT_DOUBLE_EQ(r.accuracy, 12.0 / 16);
  EXPECT_NEAR(r.macro_f1, (10.0 / 13 + 0.6 + 8.0 / 9) / 3, 1e-12);
  EXPECT_NEAR(r.macro_recall, (5.0 / 6 + 0.5 + 1.0) / 3, 1e-12);
  const Eigen::MatrixXd p = m.RowPercent();
  EXPECT_NEAR(p(1, 0), 100.0 * 2 / 6, 1e-12);
  EXPECT_NEAR(p.row(2).sum(), 100.0, 1e-12);
}

TEST(Metrics, NeverPredictedClassScoresZeroNotNaN) {
  ConfusionMatrix m({"x", "y"});
  m.Add(0, 0, 3);
  m.Add(1, 0, 2);  // y is never predicted
  const RecognitionMetrics r = ComputeMetrics(m);
  EXPECT_EQ(r.per_class[1].precision, 0.0);
  EXPECT_EQ(r.per_class[1].recall, 0.0);
  EXPECT_EQ(r.per_class[1].f1, 0.0);
  EXPECT_DOUBLE_EQ(r.per_class[0].precision, 0.6);
  EXPECT_DOUBLE_EQ(r.accuracy, 0.6);
}

TEST(Metrics, PerfectClassifier) {
  ConfusionMatrix m({"p", "q"});
  m.Add(0, 0, 7);
  m.Add(1, 1, 9);
  const RecognitionMetrics r = ComputeMetrics(m);
  EXPECT_DOUBLE_EQ(r.macro_f1, 1.0);
  EXPECT_DOUBLE_EQ(r.accuracy, 1.0);
}

TEST(Metrics, RejectsBadIndicesAndNoClasses) {
  ConfusionMatrix m({"p"});
  EXPECT_THROW(m.Add(0, 1), std::invalid_argument);
  EXPECT_THROW(ConfusionMatrix({}), std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::perception
