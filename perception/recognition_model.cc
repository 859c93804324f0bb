#include "perception/recognition_model.h"

#include <opencv2/core/eigen.hpp>
#include <opencv2/core/persistence.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/enum_names.h"

namespace sortcell::perception {
namespace {

constexpr const char* kFormat = "sortcell-recognition-model";

cv::Mat ToMat(const Eigen::VectorXf& v) {
  cv::Mat m;
  cv::eigen2cv(v, m);
  return m;
}

template <typename T>
cv::Mat IntOrDoubleRow(const std::vector<T>& v) {
  return cv::Mat(v, true).reshape(1, 1);
}

struct Reader {
  const std::filesystem::path& file;
  cv::FileNode root;

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument("model '" + file.string() + "': " + what);
  }
  cv::FileNode Node(const cv::FileNode& parent, const std::string& key) const {
    cv::FileNode n = parent[key];
    if (n.empty() || n.isNone()) Fail("missing key '" + key + "'");
    return n;
  }
  std::string String(const cv::FileNode& parent, const std::string& key) const {
    cv::FileNode n = Node(parent, key);
    if (!n.isString()) Fail("key '" + key + "' is not a string");
    return n.string();
  }
  double Number(const cv::FileNode& parent, const std::string& key) const {
    cv::FileNode n = Node(parent, key);
    if (!n.isReal() && !n.isInt()) Fail("key '" + key + "' is not a number");
    return n.real();
  }
  /// A whole number an int holds (casting any other to int is undefined behaviour).
  int Integer(const cv::FileNode& parent, const std::string& key) const {
    const double number = Number(parent, key);
    if (number != std::floor(number) || std::fabs(number) > std::numeric_limits<int>::max()) {
      Fail("key '" + key + "' is not a whole number");
    }
    return static_cast<int>(number);
  }
  cv::Mat Matrix(const cv::FileNode& parent, const std::string& key) const {
    cv::Mat m;
    cv::FileNode n = Node(parent, key);
    if (!n.isMap()) Fail("key '" + key + "' is not a matrix");
    n >> m;
    if (m.empty()) Fail("key '" + key + "' is an empty matrix");
    return m;
  }
  template <typename T>
  std::vector<T> Row(const cv::FileNode& parent, const std::string& key, int type) const {
    cv::Mat m = Matrix(parent, key);
    if (m.type() != type || m.rows != 1) Fail("key '" + key + "' has the wrong type or shape");
    return std::vector<T>(m.ptr<T>(0), m.ptr<T>(0) + m.cols);
  }
};

// The descriptor parameters as a FileStorage map: one entry per VisitDescriptorParams key.
void WriteDescriptorParams(cv::FileStorage& fs, const DescriptorParams& params) {
  fs << "descriptor_params"
     << "{";
  VisitDescriptorParams(params, [&](const char* key, auto value) { fs << key << value; });
  fs << "}";
}

DescriptorParams ReadDescriptorParams(const Reader& r) {
  const cv::FileNode node = r.Node(r.root, "descriptor_params");
  DescriptorParams params;
  VisitDescriptorParams(params, [&](const char* key, auto& value) {
    using T = std::remove_reference_t<decltype(value)>;
    if constexpr (std::is_integral_v<T>) {
      value = static_cast<T>(r.Integer(node, key));
    } else {
      value = static_cast<T>(r.Number(node, key));
    }
  });
  return params;
}

// The file opened for reading: a JSON FileStorage, or invalid_argument naming the file.
cv::FileStorage OpenModelFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::invalid_argument("model '" + file.string() + "': no such file");
  }
  cv::FileStorage fs;
  try {
    fs.open(file.string(), cv::FileStorage::READ | cv::FileStorage::FORMAT_JSON);
  } catch (const cv::Exception& e) {
    throw std::invalid_argument("model '" + file.string() + "': damaged or not a model file (" + e.err + ")");
  }
  if (!fs.isOpened()) throw std::invalid_argument("model '" + file.string() + "': damaged or not a model file");
  return fs;
}

// "format" and "version" say this build can read the file.
void CheckFormat(const Reader& r) {
  const cv::FileNode format = r.root["format"];
  if (format.empty() || !format.isString() || format.string() != kFormat) {
    r.Fail(std::string("not a SortCell recognition model (expected \"format\": \"") + kFormat + "\")");
  }
  const double version = r.Number(r.root, "version");
  if (version != kModelFormatVersion && version != 1) {
    std::ostringstream message;
    message << "format version " << version << ", this build reads versions 1 to " << kModelFormatVersion;
    r.Fail(message.str());
  }
}

// Descriptor kind (checked against `expected`), label kind and class names.
void ReadClasses(const Reader& r, std::optional<DescriptorKind> expected, RecognitionModel& model) {
  try {
    model.descriptor = ParseDescriptorKind(r.String(r.root, "descriptor"));
    model.label_kind = ParseLabelKind(r.String(r.root, "label_kind"));
  } catch (const std::invalid_argument& e) {
    r.Fail(e.what());
  }
  if (expected && *expected != model.descriptor) {
    r.Fail("trained for descriptor '" + DescriptorName(model.descriptor) + "', expected '" + DescriptorName(*expected) +
           "'");
  }
  const cv::FileNode classes = r.Node(r.root, "classes");
  if (!classes.isSeq()) r.Fail("key 'classes' is not a list");
  for (const auto& c : classes) {
    if (!c.isString()) r.Fail("key 'classes' holds a non-string");
    model.classes.push_back(c.string());
  }
}

// Per-feature scaling, one entry per feature of the model's descriptor.
FeatureScaling ReadScaling(const Reader& r, DescriptorKind descriptor) {
  const cv::FileNode s = r.Node(r.root, "scaling");
  FeatureScaling scaling;
  cv::Mat min = r.Matrix(s, "min"), scale = r.Matrix(s, "scale");
  if (min.type() != CV_32F || scale.type() != CV_32F || min.cols != 1 || scale.cols != 1) {
    r.Fail("scaling vectors have the wrong type or shape");
  }
  cv::cv2eigen(min, scaling.min);
  cv::cv2eigen(scale, scaling.scale);
  if (scaling.min.size() != DescriptorSize(descriptor)) {
    r.Fail("scaling has " + std::to_string(scaling.min.size()) + " features, descriptor '" +
           DescriptorName(descriptor) + "' has " + std::to_string(DescriptorSize(descriptor)));
  }
  return scaling;
}

// The libsvm model's arrays (checked for consistency by SvmClassifier::FromArrays).
SvmClassifier::Arrays ReadSvmArrays(const Reader& r) {
  const cv::FileNode v = r.Node(r.root, "svm");
  SvmClassifier::Arrays a;
  a.C = r.Number(v, "C");
  a.gamma = r.Number(v, "gamma");
  a.label = r.Row<int>(v, "label", CV_32S);
  a.nSV = r.Row<int>(v, "nSV", CV_32S);
  a.rho = r.Row<double>(v, "rho", CV_64F);
  a.probA = r.Row<double>(v, "probA", CV_64F);
  a.probB = r.Row<double>(v, "probB", CV_64F);
  cv::Mat sv_coef = r.Matrix(v, "sv_coef"), sv = r.Matrix(v, "sv");
  if (sv_coef.type() != CV_64F || sv.type() != CV_64F) r.Fail("support vectors are not double matrices");
  Eigen::MatrixXd coef;
  cv::cv2eigen(sv_coef, coef);
  a.sv_coef = coef;
  cv::cv2eigen(sv, a.sv);
  return a;
}

void WriteFamiliarity(cv::FileStorage& fs, const Familiarity& f) {
  cv::Mat reference, scale;
  cv::eigen2cv(f.reference, reference);
  cv::eigen2cv(f.block_scale, scale);
  fs << "familiarity"
     << "{"
     << "reference" << reference << "block_scale" << scale << "held_out" << cv::Mat(f.held_out, true).reshape(1, 1)
     << "colour_per_voxel" << static_cast<int>(f.colour_per_voxel) << "}";
}

// Optional: a model file of before has none (every view is then familiar).
Familiarity ReadFamiliarity(const Reader& r) {
  const cv::FileNode node = r.root["familiarity"];
  Familiarity f;
  if (node.empty() || node.isNone()) return f;
  const cv::Mat reference = r.Matrix(node, "reference"), scale = r.Matrix(node, "block_scale");
  if (reference.type() != CV_32F || scale.type() != CV_32F || scale.cols != 1) {
    r.Fail("familiarity arrays have the wrong type or shape");
  }
  cv::cv2eigen(reference, f.reference);
  cv::cv2eigen(scale, f.block_scale);
  f.held_out = r.Row<float>(node, "held_out", CV_32F);
  // Absent in a model file of before: its colour was counted per point.
  const cv::FileNode per_voxel = node["colour_per_voxel"];
  f.colour_per_voxel = false;
  if (!per_voxel.empty() && !per_voxel.isNone()) {
    const int value = r.Integer(node, "colour_per_voxel");
    if (value != 0 && value != 1) r.Fail("key 'colour_per_voxel' is not 0 or 1");
    f.colour_per_voxel = value == 1;
  }
  try {
    f.Check();
  } catch (const std::invalid_argument& e) {
    r.Fail(e.what());
  }
  return f;
}

}  // namespace

constexpr EnumNames<LabelKind, 2> kLabelKindNames{
    {{LabelKind::kCategory, "category"}, {LabelKind::kInstance, "instance"}}};

const char* ToString(LabelKind kind) { return NameOf(kLabelKindNames, kind); }

Recognition Recognise(const Cloud& object_C, const RecognitionModel& model, double reject_below) {
  Recognition r;
  DescriptorParts parts = ComputeDescriptorParts(object_C, model.params);
  r.status = parts.status;
  r.detail = std::move(parts.detail);
  if (!r.described()) return r;
  r.result = model.Classify(parts);
  r.rejected = Rejected(r.result.confidence, reject_below);
  return r;
}

LabelKind ParseLabelKind(const std::string& name) { return ParseName(kLabelKindNames, name, "label kind"); }

RecognitionModel::Result RecognitionModel::Classify(const DescriptorParts& parts) const {
  const Prediction p = classifier.Predict(AssembleDescriptor(parts, descriptor));
  Result result;
  result.name = classes.at(p.label);
  result.label = p.label;
  result.probability = p.confidence;
  result.familiarity = familiarity.Of(RawParts(parts));
  result.confidence = result.probability * result.familiarity;
  for (size_t c = 0; c < p.probabilities.size(); ++c) result.ranked.push_back({classes.at(c), p.probabilities[c]});
  std::stable_sort(result.ranked.begin(), result.ranked.end(),
                   [](const Ranked& a, const Ranked& b) { return a.probability > b.probability; });
  return result;
}

void SaveModel(const std::filesystem::path& file, const RecognitionModel& model) {
  const SvmClassifier::Arrays a = model.classifier.ToArrays();
  cv::Mat sv, sv_coef;
  cv::eigen2cv(a.sv, sv);
  cv::eigen2cv(Eigen::MatrixXd(a.sv_coef), sv_coef);
  std::string text;
  try {  // Into memory first: OpenCV does not check its own file writes.
    cv::FileStorage fs(".json", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_JSON |
                                    cv::FileStorage::WRITE_BASE64);
    fs << "format" << kFormat << "version" << kModelFormatVersion;
    fs << "descriptor" << DescriptorName(model.descriptor) << "label_kind" << ToString(model.label_kind);
    fs << "classes"
       << "[";
    for (const auto& c : model.classes) fs << c;
    fs << "]";
    WriteDescriptorParams(fs, model.params);
    fs << "training"
       << "{"
       << "samples" << model.train_samples << "cv_accuracy" << model.cv_accuracy << "}";
    fs << "scaling"
       << "{"
       << "min" << ToMat(model.classifier.scaling().min) << "scale" << ToMat(model.classifier.scaling().scale) << "}";
    fs << "svm"
       << "{"
       << "C" << a.C << "gamma" << a.gamma << "label" << IntOrDoubleRow(a.label) << "nSV" << IntOrDoubleRow(a.nSV)
       << "rho" << IntOrDoubleRow(a.rho) << "probA" << IntOrDoubleRow(a.probA) << "probB" << IntOrDoubleRow(a.probB)
       << "sv_coef" << sv_coef << "sv" << sv << "}";
    if (!model.familiarity.empty()) WriteFamiliarity(fs, model.familiarity);
    text = fs.releaseAndGetString();
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write model '" + file.string() + "': " + e.err);
  }
  errno = 0;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();  // Flushes: a full disk shows here.
  if (!out) {
    throw std::runtime_error("cannot write model '" + file.string() + "'" +
                             (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
  }
}

RecognitionModel LoadModel(const std::filesystem::path& file, std::optional<DescriptorKind> expected) {
  cv::FileStorage fs = OpenModelFile(file);
  const Reader r{file, fs.root()};
  try {
    CheckFormat(r);
    RecognitionModel model;
    ReadClasses(r, expected, model);
    model.params = ReadDescriptorParams(r);
    const cv::FileNode training = r.Node(r.root, "training");
    model.train_samples = r.Integer(training, "samples");
    model.cv_accuracy = r.Number(training, "cv_accuracy");
    FeatureScaling scaling = ReadScaling(r, model.descriptor);
    const SvmClassifier::Arrays arrays = ReadSvmArrays(r);
    model.familiarity = ReadFamiliarity(r);
    try {
      model.classifier = SvmClassifier::FromArrays(arrays, std::move(scaling), static_cast<int>(model.classes.size()));
    } catch (const std::invalid_argument& e) {
      r.Fail(e.what());
    }
    return model;
  } catch (const cv::Exception& e) {
    r.Fail("damaged (" + e.err + ")");
  }
}

}  // namespace sortcell::perception
