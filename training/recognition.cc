#include "training/recognition.h"

#include <opencv2/imgproc.hpp>

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "files/output_dir.h"
#include "assets/image_file.h"
#include "common/enum_names.h"

namespace sortcell::training {
namespace {

std::vector<int> AllRows(const Dataset& d, std::vector<int> rows) {
  if (rows.empty()) {
    rows.resize(d.samples.size());
    std::iota(rows.begin(), rows.end(), 0);
  }
  return rows;
}

int ClassIndex(const std::vector<std::string>& classes, const std::string& name) {
  const auto it = std::find(classes.begin(), classes.end(), name);
  return it == classes.end() ? -1 : static_cast<int>(it - classes.begin());
}

// Cross-validation group of a sample: neighbouring frames are near-duplicates, so a whole contiguous
// third of a revolution (or a whole scene, or a whole instance) goes to one fold.
std::string GroupKey(const Sample& s, Grouping group_by, int views) {
  if (group_by == Grouping::kInstance) return s.instance;
  if (s.scene >= 0) return "scene " + std::to_string(s.scene);
  const int part = views > 0 ? 3 * s.frame / views : 0;
  return s.instance + "/" + std::to_string(s.elevation_deg) + "/" + std::to_string(part);
}

// The descriptor parameters that differ: "<key>: dataset <value>, model <value>; ...".
std::string ParamsDifference(const perception::DescriptorParams& dataset, const perception::DescriptorParams& model) {
  std::vector<std::pair<std::string, double>> values;
  perception::VisitDescriptorParams(dataset, [&](const char* key, auto value) { values.emplace_back(key, value); });
  std::string difference;
  size_t i = 0;
  perception::VisitDescriptorParams(model, [&](const char*, auto value) {
    const auto& [key, dataset_value] = values[i++];
    if (dataset_value == value) return;
    difference += fmt::format("{}{}: dataset {:g}, model {:g}", difference.empty() ? "" : "; ", key, dataset_value,
                              static_cast<double>(value));
  });
  return difference;
}

std::string Percent(double x) { return fmt::format("{:.2f}%", 100 * x); }

std::string Fixed(double x, int digits) { return fmt::format("{:.{}f}", x, digits); }

cv::Mat HeatMap(const Evaluation& e) {
  const auto& classes = e.confusion.classes();
  const int n = static_cast<int>(classes.size()), cell = 56, left = 110, top = 70;
  cv::Mat image(top + n * cell + 10, left + n * cell + 10, CV_8UC3, cv::Scalar(255, 255, 255));
  const Eigen::MatrixXd percent = e.confusion.RowPercent();
  cv::Mat level(1, 1, CV_8UC1), colour;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      level.at<uchar>(0, 0) = static_cast<uchar>(std::lround(2.55 * percent(r, c)));
      cv::applyColorMap(level, colour, cv::COLORMAP_VIRIDIS);
      const cv::Vec3b v = colour.at<cv::Vec3b>(0, 0);
      const cv::Rect box(left + c * cell, top + r * cell, cell, cell);
      cv::rectangle(image, box, cv::Scalar(v[0], v[1], v[2]), cv::FILLED);
      const cv::Scalar ink = percent(r, c) > 60 ? cv::Scalar(0, 0, 0) : cv::Scalar(255, 255, 255);
      cv::putText(image, Fixed(percent(r, c), percent(r, c) >= 99.995 ? 0 : 1), {box.x + 6, box.y + cell / 2 + 5},
                  cv::FONT_HERSHEY_SIMPLEX, 0.42, ink, 1, cv::LINE_AA);
    }
    cv::putText(image, classes[r].substr(0, 12), {6, top + r * cell + cell / 2 + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    cv::putText(image, classes[r].substr(0, 7), {left + r * cell + 3, top - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  cv::putText(image, perception::DescriptorTitle(e.descriptor) + " (rows actual, columns predicted, %)", {6, 22},
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return image;
}

// Per class recall, precision, accuracy and F1, the descriptors side by side; macro averages and
// overall accuracy at the bottom.
std::string PerClassTable(const std::vector<Evaluation>& evaluations) {
  const auto& classes = evaluations.front().confusion.classes();
  std::ostringstream table;
  table << "| |";
  for (const auto& e : evaluations) {
    const std::string t = perception::DescriptorTitle(e.descriptor);
    table << " " << t << " recall | precision | accuracy | F1 |";
  }
  table << "\n|---|";
  for (size_t i = 0; i < evaluations.size(); ++i) table << "---:|---:|---:|---:|";
  table << "\n";
  for (size_t c = 0; c < classes.size(); ++c) {
    table << "| " << classes[c] << " vs. all |";
    for (const auto& e : evaluations) {
      const auto& k = e.metrics.per_class[c];
      table << " " << Percent(k.recall) << " | " << Percent(k.precision) << " | " << Percent(k.accuracy) << " | "
            << Fixed(k.f1, 4) << " |";
    }
    table << "\n";
  }
  table << "| **macro average** |";
  for (const auto& e : evaluations) {
    table << " " << Percent(e.metrics.macro_recall) << " | " << Percent(e.metrics.macro_precision) << " | "
          << Percent(e.metrics.macro_accuracy) << " | **" << Fixed(e.metrics.macro_f1, 4) << "** |";
  }
  table << "\n| overall accuracy |";
  for (const auto& e : evaluations) table << " | | " << Percent(e.metrics.accuracy) << " | |";
  table << "\n";
  return table.str();
}

// Training and test sizes, SVM settings and confidence per descriptor.
std::string SvmTable(const std::vector<Evaluation>& evaluations) {
  std::ostringstream out;
  out << "| descriptor | train | test | SVM C | SVM gamma | grouped-CV accuracy | mean confidence |\n"
         "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& e : evaluations) {
    const std::string C = e.trials > 1 ? "per trial" : fmt::format("{:g}", e.C);
    const std::string gamma = e.trials > 1 ? "per trial" : fmt::format("{:g}", e.gamma);
    out << "| " << perception::DescriptorTitle(e.descriptor) << " | " << e.train_samples << " | " << e.test_samples
        << " | " << C << " | " << gamma << " | " << Percent(e.cv_accuracy) << " | " << Fixed(e.mean_confidence, 3)
        << " |\n";
  }
  return out.str();
}

// One descriptor's confusion matrix in percent of the row, as a Markdown section.
std::string ConfusionSection(const Evaluation& e) {
  const auto& classes = e.confusion.classes();
  std::ostringstream out;
  out << "\n### Confusion matrix, " << perception::DescriptorTitle(e.descriptor)
      << " (rows actual, columns predicted, % of the row)\n\n| actual \\ predicted |";
  for (const auto& c : classes) out << " " << c << " |";
  out << "\n|---|";
  for (size_t i = 0; i < classes.size(); ++i) out << "---:|";
  out << "\n";
  const Eigen::MatrixXd p = e.confusion.RowPercent();
  for (size_t r = 0; r < classes.size(); ++r) {
    out << "| " << classes[r] << " |";
    for (size_t c = 0; c < classes.size(); ++c) {
      const std::string cell = p(r, c) == 0 ? "0" : Fixed(p(r, c), 2) + "%";
      out << " " << (r == c ? "**" + cell + "**" : cell) << " |";
    }
    out << "\n";
  }
  return out.str();
}

// confusion_<descriptor>.csv: the same matrix, 4 decimals.
std::string ConfusionCsv(const Evaluation& e) {
  const auto& classes = e.confusion.classes();
  const Eigen::MatrixXd p = e.confusion.RowPercent();
  std::ostringstream csv;
  csv << files::CsvField("actual\\predicted");
  for (const auto& c : classes) csv << "," << files::CsvField(c);
  csv << "\n";
  for (size_t r = 0; r < classes.size(); ++r) {
    csv << files::CsvField(classes[r]);
    for (size_t c = 0; c < classes.size(); ++c) csv << "," << Fixed(p(r, c), 4);
    csv << "\n";
  }
  return csv.str();
}

// The metrics.csv rows of one evaluation: one per class, then its macro averages.
std::string MetricsCsvRows(const Evaluation& e) {
  const std::string name = files::CsvField(perception::DescriptorName(e.descriptor));
  const auto& classes = e.confusion.classes();
  std::ostringstream csv;
  for (size_t c = 0; c < classes.size(); ++c) {
    const auto& k = e.metrics.per_class[c];
    csv << name << "," << files::CsvField(classes[c]) << "," << k.recall << "," << k.precision << "," << k.accuracy
        << "," << k.f1 << "," << k.tp << "," << k.fp << "," << k.fn << "," << k.tn << "\n";
  }
  csv << name << ",macro," << e.metrics.macro_recall << "," << e.metrics.macro_precision << ","
      << e.metrics.macro_accuracy << "," << e.metrics.macro_f1 << ",,,,\n";
  return csv.str();
}

// The familiarity of the rows whose samples fit it (Sample::fits_familiarity), of all when every one does.
perception::Familiarity FitFamiliarity(const Dataset& dataset, const std::vector<int>& rows,
                                       const Eigen::MatrixXf& raw_parts, const std::vector<int>& groups) {
  std::vector<int> fitting;
  std::vector<int> fitting_groups;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!dataset.samples.at(rows[i]).fits_familiarity) continue;
    fitting.push_back(static_cast<int>(i));
    fitting_groups.push_back(groups[i]);
  }
  if (fitting.empty()) {
    throw std::invalid_argument("training: none of the " + std::to_string(rows.size()) +
                                " samples trained on fits the familiarity (all were captured with --classifier-only): "
                                "train them together with views captured without it");
  }
  return perception::Familiarity::Fit(raw_parts(fitting, Eigen::all), fitting_groups);
}

}  // namespace

constexpr EnumNames<Grouping, 2> kGroupingNames{{{Grouping::kSequence, "sequence"}, {Grouping::kInstance, "instance"}}};

const char* ToString(Grouping grouping) { return NameOf(kGroupingNames, grouping); }

Grouping ParseGrouping(const std::string& name) { return ParseName(kGroupingNames, name, "grouping"); }

constexpr EnumNames<ExperimentSplit, 2> kExperimentSplitNames{
    {{ExperimentSplit::kPaper, "paper"}, {ExperimentSplit::kUnseenInstance, "unseen-instance"}}};

const char* ToString(ExperimentSplit split) { return NameOf(kExperimentSplitNames, split); }

ExperimentSplit ParseExperimentSplit(const std::string& name) {
  return ParseName(kExperimentSplitNames, name, "split");
}

perception::RecognitionModel TrainModel(const Dataset& dataset, std::vector<int> rows, const TrainRequest& request) {
  rows = AllRows(dataset, std::move(rows));
  perception::RecognitionModel model;
  model.descriptor = request.descriptor;
  model.params = dataset.params;
  model.label_kind = request.label_kind;
  for (int r : rows) {
    const std::string& label = Dataset::Label(dataset.samples.at(r), request.label_kind);
    if (std::find(model.classes.begin(), model.classes.end(), label) == model.classes.end())
      model.classes.push_back(label);
  }
  const int dim = perception::DescriptorSize(request.descriptor);
  Eigen::MatrixXf samples(static_cast<Eigen::Index>(rows.size()), dim);
  Eigen::MatrixXf raw_parts(static_cast<Eigen::Index>(rows.size()),
                            perception::DescriptorSize(perception::DescriptorKind::kColorCvfh));
  std::vector<int> labels, groups;
  std::map<std::string, int> group_ids;
  for (size_t i = 0; i < rows.size(); ++i) {
    const Sample& s = dataset.samples.at(rows[i]);
    samples.row(static_cast<Eigen::Index>(i)) = perception::AssembleDescriptor(s.parts, request.descriptor).transpose();
    raw_parts.row(static_cast<Eigen::Index>(i)) = perception::RawParts(s.parts).transpose();
    labels.push_back(ClassIndex(model.classes, Dataset::Label(s, request.label_kind)));
    groups.push_back(group_ids.emplace(GroupKey(s, request.group_by, dataset.views), group_ids.size()).first->second);
  }
  model.classifier = perception::SvmClassifier::Train(samples, labels, groups, static_cast<int>(model.classes.size()),
                                                      request.grid, perception::DescriptorBlocks(request.descriptor));
  model.familiarity = FitFamiliarity(dataset, rows, raw_parts, groups);
  model.train_samples = static_cast<int>(rows.size());
  for (const auto& score : model.classifier.cv_scores())
    model.cv_accuracy = std::max(model.cv_accuracy, score.accuracy);
  return model;
}

void CheckDescriptorParams(const perception::RecognitionModel& model, const Dataset& dataset,
                           const std::string& dataset_name) {
  if (!perception::SameDescriptorParams(model.params, dataset.params)) {
    throw std::invalid_argument("dataset '" + dataset_name +
                                "': its descriptors were computed with other parameters than the model's (" +
                                ParamsDifference(dataset.params, model.params) + ")");
  }
}

Evaluation EvaluateModel(const perception::RecognitionModel& model, const Dataset& dataset, std::vector<int> rows,
                         const std::string& dataset_name) {
  rows = AllRows(dataset, std::move(rows));
  CheckDescriptorParams(model, dataset, dataset_name);
  Evaluation e{model.descriptor,
               perception::ConfusionMatrix(model.classes),
               {},
               model.classifier.C(),
               model.classifier.gamma(),
               model.cv_accuracy,
               model.train_samples,
               static_cast<int>(rows.size()),
               0};
  for (int r : rows) {
    const Sample& s = dataset.samples.at(r);
    const std::string& truth = Dataset::Label(s, model.label_kind);
    const int actual = ClassIndex(model.classes, truth);
    if (actual < 0) {
      throw std::invalid_argument("dataset '" + dataset_name + "': sample " + std::to_string(s.id) + " is a '" + truth +
                                  "', not one of the model's " + ToString(model.label_kind) + " classes");
    }
    const auto result = model.Classify(s.parts);
    e.confusion.Add(actual, result.label);
    e.mean_confidence += result.confidence / rows.size();
  }
  e.metrics = perception::ComputeMetrics(e.confusion);
  return e;
}

Evaluation PoolEvaluations(const std::vector<Evaluation>& trials) {
  if (trials.empty()) throw std::invalid_argument("PoolEvaluations: no evaluations");
  std::vector<std::string> classes;
  for (const Evaluation& e : trials) {
    if (e.descriptor != trials.front().descriptor) throw std::invalid_argument("PoolEvaluations: mixed descriptors");
    for (const auto& name : e.confusion.classes()) {
      if (ClassIndex(classes, name) < 0) classes.push_back(name);
    }
  }
  const Evaluation& first = trials.front();
  Evaluation pooled{first.descriptor,
                    perception::ConfusionMatrix(classes),
                    {},
                    first.C,
                    first.gamma,
                    0,
                    0,
                    0,
                    0,
                    static_cast<int>(trials.size())};
  for (const Evaluation& e : trials) {
    const auto& names = e.confusion.classes();
    for (size_t r = 0; r < names.size(); ++r) {
      for (size_t c = 0; c < names.size(); ++c) {
        const int count = e.confusion.counts()(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
        if (count > 0) pooled.confusion.Add(ClassIndex(classes, names[r]), ClassIndex(classes, names[c]), count);
      }
    }
    pooled.cv_accuracy += e.cv_accuracy / trials.size();
    pooled.train_samples += e.train_samples;
    pooled.test_samples += e.test_samples;
    pooled.mean_confidence += e.mean_confidence * e.test_samples;
  }
  if (pooled.test_samples > 0) pooled.mean_confidence /= pooled.test_samples;
  pooled.metrics = perception::ComputeMetrics(pooled.confusion);
  return pooled;
}

nlohmann::json EvaluationJson(const Evaluation& e) {
  const auto& classes = e.confusion.classes();
  nlohmann::json per_class = nlohmann::json::object();
  for (size_t c = 0; c < classes.size(); ++c) {
    const auto& k = e.metrics.per_class[c];
    per_class[classes[c]] = {{"recall", k.recall},
                             {"precision", k.precision},
                             {"accuracy", k.accuracy},
                             {"f1", k.f1},
                             {"tp", k.tp},
                             {"fp", k.fp},
                             {"fn", k.fn},
                             {"tn", k.tn}};
  }
  nlohmann::json counts = nlohmann::json::array(), percent = nlohmann::json::array();
  const Eigen::MatrixXd p = e.confusion.RowPercent();
  for (Eigen::Index r = 0; r < p.rows(); ++r) {
    nlohmann::json cr = nlohmann::json::array(), pr = nlohmann::json::array();
    for (Eigen::Index c = 0; c < p.cols(); ++c) {
      cr.push_back(e.confusion.counts()(r, c));
      pr.push_back(p(r, c));
    }
    counts.push_back(cr);
    percent.push_back(pr);
  }
  return {{"macro_f1", e.metrics.macro_f1},
          {"accuracy", e.metrics.accuracy},
          {"macro_recall", e.metrics.macro_recall},
          {"macro_precision", e.metrics.macro_precision},
          {"macro_accuracy", e.metrics.macro_accuracy},
          {"per_class", per_class},
          {"confusion", {{"classes", classes}, {"counts", counts}, {"percent", percent}}},
          {"mean_confidence", e.mean_confidence},
          {"svm", {{"C", e.C}, {"gamma", e.gamma}, {"cv_accuracy", e.cv_accuracy}}},
          {"train_samples", e.train_samples},
          {"test_samples", e.test_samples}};
}

std::string WriteRecognitionReport(const std::filesystem::path& dir, const std::string& title,
                                   const std::vector<Evaluation>& evaluations, const std::string& preface) {
  if (evaluations.empty()) return "";
  std::string markdown = "## " + title + "\n\n" + (preface.empty() ? "" : preface + "\n") + PerClassTable(evaluations) +
                         "\n" + SvmTable(evaluations);
  std::string metrics_csv = "descriptor,class,recall,precision,accuracy,f1,tp,fp,fn,tn\n";
  for (const auto& e : evaluations) {
    const std::string name = perception::DescriptorName(e.descriptor);
    markdown += ConfusionSection(e);
    metrics_csv += MetricsCsvRows(e);
    files::WriteTextFile(dir / ("confusion_" + name + ".csv"), ConfusionCsv(e));
    const std::filesystem::path png = dir / ("confusion_" + name + ".png");
    if (!assets::WritePng(png, HeatMap(e))) throw std::runtime_error("cannot write '" + png.string() + "'");
  }
  files::WriteTextFile(dir / "metrics.csv", metrics_csv);
  files::WriteTextFile(dir / "tables.md", markdown);
  return markdown;
}

}  // namespace sortcell::training
