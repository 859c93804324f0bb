#include "perception/descriptor.h"

#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/enum_names.h"
#include "common/wall_clock.h"

namespace sortcell::perception {
namespace {

// Divides v[first, first + size) by `divisor` (an empty block stays zero).
void DivideBlock(Eigen::VectorXf& v, int first, int size, float divisor) {
  if (divisor > 0) v.segment(first, size) /= divisor;
}

Eigen::VectorXf NormalisedCvfh(const Eigen::VectorXf& raw) {
  Eigen::VectorXf cvfh = raw;
  for (const auto& [first, size] : kCvfhBlocks) DivideBlock(cvfh, first, size, raw.segment(first, size).sum());
  return cvfh;
}

}  // namespace

constexpr EnumNames<DescriptorKind, 3> kDescriptorKindNames{{{DescriptorKind::kCvfh, "cvfh"},
                                                             {DescriptorKind::kColorCvfh, "color-cvfh"},
                                                             {DescriptorKind::kColorCvfhNorm, "color-cvfh-norm"}}};

std::string DescriptorName(DescriptorKind kind) { return NameOf(kDescriptorKindNames, kind); }

constexpr EnumNames<DescriptorKind, 3> kDescriptorKindTitles{
    {{DescriptorKind::kCvfh, "CVFH"},
     {DescriptorKind::kColorCvfh, "Color-CVFH"},
     {DescriptorKind::kColorCvfhNorm, "Color-CVFH (normalization)"}}};

std::string DescriptorTitle(DescriptorKind kind) { return NameOf(kDescriptorKindTitles, kind); }

DescriptorKind ParseDescriptorKind(const std::string& name) {
  return ParseName(kDescriptorKindNames, name, "descriptor");
}

int DescriptorSize(DescriptorKind kind) { return kind == DescriptorKind::kCvfh ? kCvfhBins : kHsvBins + kCvfhBins; }

std::vector<FeatureBlock> DescriptorBlocks(DescriptorKind kind) {
  std::vector<FeatureBlock> blocks;
  int colour = 0;
  if (kind != DescriptorKind::kCvfh) {
    blocks = {{0, kHueBins}, {kHueBins, kSaturationBins}, {kHueBins + kSaturationBins, kValueBins}};
    colour = kHsvBins;
  }
  for (const auto& [first, size] : kCvfhBlocks) blocks.push_back({colour + first, size});
  return blocks;
}

bool SameDescriptorParams(const DescriptorParams& a, const DescriptorParams& b) {
  std::vector<double> values_a, values_b;
  VisitDescriptorParams(a, [&](const char*, auto value) { values_a.push_back(value); });
  VisitDescriptorParams(b, [&](const char*, auto value) { values_b.push_back(value); });
  return values_a == values_b;
}

DescriptorParts ComputeDescriptorParts(const Cloud& object_C, const DescriptorParams& params) {
  DescriptorParts parts;
  CvfhResult cvfh = ComputeCvfh(object_C, params.cvfh);
  parts.status = cvfh.status;
  parts.detail = std::move(cvfh.detail);
  parts.cvfh = std::move(cvfh.histogram);
  parts.cvfh_regions = cvfh.regions;
  parts.normals_s = cvfh.normals_s;
  parts.cvfh_s = cvfh.cvfh_s;
  if (parts.status != DescriptorStatus::kOk) return parts;
  const auto t = std::chrono::steady_clock::now();
  parts.hsv = HsvHistogram(object_C, params.hsv);
  parts.hsv_s = SecondsSince(t);
  return parts;
}

Eigen::VectorXf AssembleDescriptor(const DescriptorParts& parts, DescriptorKind kind) {
  if (parts.status != DescriptorStatus::kOk) {
    throw std::invalid_argument("descriptor parts: " + parts.detail + " (status " + ToString(parts.status) +
                                "): no descriptor to assemble");
  }
  if (parts.hsv.size() != kHsvBins || parts.cvfh.size() != kCvfhBins) {
    throw std::invalid_argument("descriptor parts have " + std::to_string(parts.hsv.size()) + " HSV and " +
                                std::to_string(parts.cvfh.size()) + " CVFH bins, expected 192 and 308");
  }
  if (kind == DescriptorKind::kCvfh) return NormalisedCvfh(parts.cvfh);
  Eigen::VectorXf out(kHsvBins + kCvfhBins);
  if (kind == DescriptorKind::kColorCvfh) {
    out << parts.hsv, parts.cvfh;
    return out;
  }
  Eigen::VectorXf hsv = parts.hsv;
  const float points = parts.hsv.segment(kHueBins, kSaturationBins).sum();  // S counts every point.
  DivideBlock(hsv, 0, kHueBins, points);
  DivideBlock(hsv, kHueBins, kSaturationBins, points);
  DivideBlock(hsv, kHueBins + kSaturationBins, kValueBins, points);
  out << hsv, NormalisedCvfh(parts.cvfh);
  return out;
}

}  // namespace sortcell::perception
