#include "perception/metrics.h"

#include <stdexcept>

namespace sortcell::perception {
namespace {

double Ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

}  // namespace

ConfusionMatrix::ConfusionMatrix(std::vector<std::string> classes)
    : classes_(std::move(classes)), counts_(Eigen::MatrixXi::Zero(classes_.size(), classes_.size())) {
  if (classes_.empty()) throw std::invalid_argument("confusion matrix: no classes");
}

void ConfusionMatrix::Add(int actual, int predicted, int count) {
  const int n = static_cast<int>(classes_.size());
  if (actual < 0 || actual >= n || predicted < 0 || predicted >= n) {
    throw std::invalid_argument("confusion matrix: class index (" + std::to_string(actual) + ", " +
                                std::to_string(predicted) + ") outside [0, " + std::to_string(n) + ")");
  }
  counts_(actual, predicted) += count;
}

Eigen::MatrixXd ConfusionMatrix::RowPercent() const {
  Eigen::MatrixXd percent = counts_.cast<double>();
  for (Eigen::Index r = 0; r < percent.rows(); ++r) {
    const double sum = percent.row(r).sum();
    if (sum > 0) percent.row(r) *= 100.0 / sum;
  }
  return percent;
}

RecognitionMetrics ComputeMetrics(const ConfusionMatrix& confusion) {
  const Eigen::MatrixXi& m = confusion.counts();
  const int n = static_cast<int>(m.rows());
  const int total = m.sum();
  RecognitionMetrics out;
  for (int c = 0; c < n; ++c) {
    ClassMetrics k;
    k.tp = m(c, c);
    k.fn = m.row(c).sum() - k.tp;
    k.fp = m.col(c).sum() - k.tp;
    k.tn = total - k.tp - k.fn - k.fp;
    k.recall = Ratio(k.tp, k.tp + k.fn);
    k.precision = Ratio(k.tp, k.tp + k.fp);
    k.accuracy = Ratio(k.tp + k.tn, total);
    k.f1 = Ratio(2 * k.precision * k.recall, k.precision + k.recall);
    out.macro_recall += k.recall / n;
    out.macro_precision += k.precision / n;
    out.macro_accuracy += k.accuracy / n;
    out.macro_f1 += k.f1 / n;
    out.per_class.push_back(k);
  }
  out.accuracy = Ratio(m.trace(), total);
  return out;
}

}  // namespace sortcell::perception
