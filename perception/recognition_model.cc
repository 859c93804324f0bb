#include "perception/recognition_model.h"

#include <opencv2/core/eigen.hpp>
#include <opencv2/core/persistence.hpp>

#include <stdexcept>

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

}  // namespace

RecognitionModel::Result RecognitionModel::Classify(const DescriptorParts& parts) const {
  const Prediction p = classifier.Predict(AssembleDescriptor(parts, descriptor));
  return {classes.at(p.label), p.confidence, p.label};
}

bool SameDescriptorParams(const DescriptorParams& a, const DescriptorParams& b) {
  const CvfhParams &x = a.cvfh, &y = b.cvfh;
  return a.hsv.min_saturation == b.hsv.min_saturation && a.hsv.min_value == b.hsv.min_value &&
         x.voxel_leaf_m == y.voxel_leaf_m && x.normal_radius_m == y.normal_radius_m &&
         x.eps_angle_rad == y.eps_angle_rad && x.curvature_threshold == y.curvature_threshold &&
         x.cluster_tolerance_m == y.cluster_tolerance_m && x.min_region_points == y.min_region_points &&
         x.min_points == y.min_points;
}

void SaveModel(const std::filesystem::path& file, const RecognitionModel& model) {
  const SvmClassifier::Arrays a = model.classifier.ToArrays();
  cv::Mat sv, sv_coef;
  cv::eigen2cv(a.sv, sv);
  cv::eigen2cv(Eigen::MatrixXd(a.sv_coef), sv_coef);
  try {
    cv::FileStorage fs(file.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_JSON);
    if (!fs.isOpened()) throw std::runtime_error("cannot open for writing");
    fs << "format" << kFormat << "version" << kModelFormatVersion;
    fs << "descriptor" << DescriptorName(model.descriptor) << "label_kind" << model.label_kind;
    fs << "classes" << "[";
    for (const auto& c : model.classes) fs << c;
    fs << "]";
    const CvfhParams& c = model.params.cvfh;
    fs << "descriptor_params" << "{"
       << "hsv_min_saturation" << model.params.hsv.min_saturation << "hsv_min_value" << model.params.hsv.min_value
       << "cvfh_voxel_leaf_m" << c.voxel_leaf_m << "cvfh_normal_radius_m" << c.normal_radius_m
       << "cvfh_eps_angle_rad" << c.eps_angle_rad << "cvfh_curvature_threshold" << c.curvature_threshold
       << "cvfh_cluster_tolerance_m" << c.cluster_tolerance_m << "cvfh_min_region_points" << c.min_region_points
       << "cvfh_min_points" << c.min_points << "}";
    fs << "training" << "{" << "samples" << model.train_samples << "cv_accuracy" << model.cv_accuracy << "}";
    fs << "scaling" << "{" << "min" << ToMat(model.classifier.scaling().min) << "scale"
       << ToMat(model.classifier.scaling().scale) << "}";
    fs << "svm" << "{" << "C" << a.C << "gamma" << a.gamma << "label" << IntOrDoubleRow(a.label) << "nSV"
       << IntOrDoubleRow(a.nSV) << "rho" << IntOrDoubleRow(a.rho) << "probA" << IntOrDoubleRow(a.probA) << "probB"
       << IntOrDoubleRow(a.probB) << "sv_coef" << sv_coef << "sv" << sv << "}";
    fs.release();
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write model '" + file.string() + "': " + e.err);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write model '" + file.string() + "': " + e.what());
  }
}

RecognitionModel LoadModel(const std::filesystem::path& file, std::optional<DescriptorKind> expected) {
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
  Reader r{file, fs.root()};
  if (!fs.isOpened()) r.Fail("damaged or not a model file");
  try {
    if (r.root["format"].empty() || !r.root["format"].isString() || r.root["format"].string() != kFormat) {
      r.Fail(std::string("not a SortCell recognition model (expected \"format\": \"") + kFormat + "\")");
    }
    const int version = static_cast<int>(r.Number(r.root, "version"));
    if (version != kModelFormatVersion) {
      r.Fail("format version " + std::to_string(version) + ", this build reads version " +
             std::to_string(kModelFormatVersion));
    }
    RecognitionModel model;
    try {
      model.descriptor = ParseDescriptorKind(r.String(r.root, "descriptor"));
    } catch (const std::invalid_argument& e) {
      r.Fail(e.what());
    }
    if (expected && *expected != model.descriptor) {
      r.Fail("trained for descriptor '" + DescriptorName(model.descriptor) + "', expected '" +
             DescriptorName(*expected) + "'");
    }
    model.label_kind = r.String(r.root, "label_kind");
    const cv::FileNode classes = r.Node(r.root, "classes");
    if (!classes.isSeq()) r.Fail("key 'classes' is not a list");
    for (const auto& c : classes) {
      if (!c.isString()) r.Fail("key 'classes' holds a non-string");
      model.classes.push_back(c.string());
    }
    const cv::FileNode p = r.Node(r.root, "descriptor_params");
    model.params.hsv.min_saturation = static_cast<int>(r.Number(p, "hsv_min_saturation"));
    model.params.hsv.min_value = static_cast<int>(r.Number(p, "hsv_min_value"));
    CvfhParams& c = model.params.cvfh;
    c.voxel_leaf_m = r.Number(p, "cvfh_voxel_leaf_m");
    c.normal_radius_m = r.Number(p, "cvfh_normal_radius_m");
    c.eps_angle_rad = r.Number(p, "cvfh_eps_angle_rad");
    c.curvature_threshold = r.Number(p, "cvfh_curvature_threshold");
    c.cluster_tolerance_m = r.Number(p, "cvfh_cluster_tolerance_m");
    c.min_region_points = static_cast<int>(r.Number(p, "cvfh_min_region_points"));
    c.min_points = static_cast<int>(r.Number(p, "cvfh_min_points"));

    const cv::FileNode t = r.Node(r.root, "training");
    model.train_samples = static_cast<int>(r.Number(t, "samples"));
    model.cv_accuracy = r.Number(t, "cv_accuracy");
    const cv::FileNode s = r.Node(r.root, "scaling");
    FeatureScaling scaling;
    cv::Mat min = r.Matrix(s, "min"), scale = r.Matrix(s, "scale");
    if (min.type() != CV_32F || scale.type() != CV_32F || min.cols != 1 || scale.cols != 1) {
      r.Fail("scaling vectors have the wrong type or shape");
    }
    cv::cv2eigen(min, scaling.min);
    cv::cv2eigen(scale, scaling.scale);
    if (scaling.min.size() != DescriptorSize(model.descriptor)) {
      r.Fail("scaling has " + std::to_string(scaling.min.size()) + " features, descriptor '" +
             DescriptorName(model.descriptor) + "' has " + std::to_string(DescriptorSize(model.descriptor)));
    }
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
    try {
      model.classifier = SvmClassifier::FromArrays(a, std::move(scaling), static_cast<int>(model.classes.size()));
    } catch (const std::invalid_argument& e) {
      r.Fail(e.what());
    }
    return model;
  } catch (const cv::Exception& e) {
    r.Fail("damaged (" + e.err + ")");
  }
}

}  // namespace sortcell::perception
