// Descriptor invariants: sizes, block sums, achromatic pixels, determinism, no state carried between
// objects, NaN handling, objects too small to describe (a status), bad input, the parameters' field list.
#include "perception/descriptor.h"

#include <gtest/gtest.h>
#include <pcl/features/pfh_tools.h>

#include <string>
#include <vector>

#include "test_clouds.h"

namespace sortcell::perception {
namespace {

using sortcell_test::CylinderFront;
using sortcell_test::SphereFront;

constexpr float kTol = 1e-4f;

TEST(HsvHistogram, BlocksCountEveryPointAndHueOnlyChromaticOnes) {
  Cloud cloud = CylinderFront(0.03, 0.1, 1.0, 200, 20, 20);  // red
  const int red = static_cast<int>(cloud.size());
  Cloud grey = CylinderFront(0.03, 0.05, 1.0, 128, 128, 128);  // achromatic
  cloud += grey;
  const Eigen::VectorXf h = HsvHistogram(cloud);
  ASSERT_EQ(h.size(), kHsvBins);
  EXPECT_EQ(h.head(kHueBins).sum(), red);
  EXPECT_EQ(h.segment(kHueBins, kSaturationBins).sum(), static_cast<float>(cloud.size()));
  EXPECT_EQ(h.tail(kValueBins).sum(), static_cast<float>(cloud.size()));
  EXPECT_EQ(h[0], red) << "pure red has OpenCV hue 0: bin 0";
  // Grey: saturation 0 (bin 0), value 128 -> bin 128 * 51 / 256 = 25.
  EXPECT_GE(h[kHueBins + 0], static_cast<float>(grey.size()));
  EXPECT_GE(h[kHueBins + kSaturationBins + 25], static_cast<float>(grey.size()));
}

TEST(HsvHistogram, GreenLandsInHueBin30) {
  const Cloud green = CylinderFront(0.03, 0.05, 1.0, 0, 255, 0);
  const Eigen::VectorXf h = HsvHistogram(green);
  // Every point is saturated and bright: all are chromatic (else the check below would pass as 0 == 0).
  ASSERT_EQ(h.head(kHueBins).sum(), static_cast<float>(green.size()));
  EXPECT_EQ(h[30], h.head(kHueBins).sum()) << "OpenCV hue of green is 60 of 180: bin 60 / 2";
}

TEST(Cvfh, ReducesRegionsToOne308VectorWithoutNaN) {
  const CvfhResult r = ComputeCvfh(CylinderFront(0.033, 0.2, 1.0, 0, 128, 0));
  ASSERT_EQ(r.histogram.size(), kCvfhBins);
  EXPECT_TRUE(r.histogram.allFinite());
  EXPECT_GE(r.regions, 1);
  // Raw counts: each angular block sums to about the point count (the centroid pair may be skipped).
  for (const auto& [first, size] : kCvfhBlocks) {
    EXPECT_NEAR(r.histogram.segment(first, size).sum(), r.points, 1.0) << "block at " << first;
  }
}

TEST(Cvfh, SameObjectSameResultWhateverCameBefore) {
  const Cloud bottle = CylinderFront(0.033, 0.2, 1.0, 0, 128, 0);
  const Cloud ball = SphereFront(0.035, 0.9, 200, 0, 0);
  const CvfhResult first = ComputeCvfh(bottle);
  ComputeCvfh(ball);  // A reused PCL estimator would carry state from here into the next call.
  const CvfhResult again = ComputeCvfh(bottle);
  EXPECT_EQ(first.regions, again.regions);
  EXPECT_TRUE(first.histogram.isApprox(again.histogram, 0.0f));
  EXPECT_FALSE(first.histogram.isApprox(ComputeCvfh(ball).histogram, 1e-3f)) << "shapes must differ";
}

TEST(Cvfh, IgnoresNaNPoints) {
  Cloud cloud = CylinderFront(0.033, 0.2, 1.0, 0, 128, 0);
  const CvfhResult clean = ComputeCvfh(cloud);
  sortcell_test::AddNan(cloud, 500);
  const CvfhResult with_nan = ComputeCvfh(cloud);
  EXPECT_TRUE(clean.histogram.isApprox(with_nan.histogram, 0.0f));
}

TEST(Cvfh, EmptyAllNanAndTinyCloudsHaveTooFewPoints) {
  Cloud empty;
  const CvfhResult none = ComputeCvfh(empty);
  EXPECT_EQ(none.status, DescriptorStatus::kTooFewPoints);
  EXPECT_NE(none.detail.find("0 valid points"), std::string::npos) << none.detail;
  EXPECT_EQ(none.histogram.size(), 0);
  Cloud nan;
  sortcell_test::AddNan(nan, 100);
  EXPECT_EQ(ComputeCvfh(nan).status, DescriptorStatus::kTooFewPoints);
  Cloud tiny;
  for (int i = 0; i < 5; ++i) tiny.push_back(sortcell_test::Point(0.01 * i, 0, 1, 1, 1, 1));
  const CvfhResult small = ComputeCvfh(tiny);
  EXPECT_EQ(small.status, DescriptorStatus::kTooFewPoints);
  EXPECT_EQ(small.points, 5);
  EXPECT_NE(small.detail.find("5 valid points"), std::string::npos) << small.detail;
  EXPECT_NE(small.detail.find("need at least 30"), std::string::npos) << small.detail;
  EXPECT_TRUE(ComputeCvfh(CylinderFront(0.033, 0.2, 1.0, 0, 128, 0)).detail.empty()) << "ok: no detail";
}

TEST(Cvfh, StatusSpellings) {
  EXPECT_STREQ(ToString(DescriptorStatus::kOk), "ok");
  EXPECT_STREQ(ToString(DescriptorStatus::kTooFewPoints), "too_few_points");
  EXPECT_STREQ(ToString(DescriptorStatus::kNoHistogram), "no_histogram");
}

TEST(Descriptor, AFragmentHasTheCvfhStatusNoPartsAndCannotBeAssembled) {
  Cloud fragment;
  for (int i = 0; i < 5; ++i) fragment.push_back(sortcell_test::Point(0.01 * i, 0, 1, 200, 20, 20));
  const DescriptorParts parts = ComputeDescriptorParts(fragment);
  EXPECT_EQ(parts.status, DescriptorStatus::kTooFewPoints);
  EXPECT_EQ(parts.detail, ComputeCvfh(fragment).detail);
  EXPECT_EQ(parts.hsv.size(), 0) << "HSV is not computed for an object that cannot be described";
  EXPECT_EQ(parts.cvfh.size(), 0);
  try {
    AssembleDescriptor(parts, DescriptorKind::kColorCvfhNorm);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "descriptor parts: " + parts.detail + " (status too_few_points): no descriptor to assemble");
  }
}

TEST(Descriptor, AssembleRejectsPartsOfTheWrongSize) {
  DescriptorParts parts;
  parts.hsv = Eigen::VectorXf::Zero(10);
  parts.cvfh = Eigen::VectorXf::Zero(kCvfhBins);
  try {
    AssembleDescriptor(parts, DescriptorKind::kCvfh);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "descriptor parts have 10 HSV and 308 CVFH bins, expected 192 and 308");
  }
}

TEST(DescriptorParams, OneListOfFieldsComparesEveryField) {
  std::vector<std::string> keys;
  const DescriptorParams defaults;
  VisitDescriptorParams(defaults, [&](const char* key, auto) { keys.push_back(key); });
  EXPECT_EQ(keys.size(), 9u);
  EXPECT_EQ(keys.front(), "hsv_min_saturation");
  EXPECT_EQ(keys.back(), "cvfh_min_points");
  EXPECT_TRUE(SameDescriptorParams(defaults, DescriptorParams{}));
  // Changing any one field makes the sets differ.
  for (size_t k = 0; k < keys.size(); ++k) {
    DescriptorParams changed;
    size_t i = 0;
    VisitDescriptorParams(changed, [&](const char*, auto& value) {
      if (i++ == k) value += 1;
    });
    EXPECT_FALSE(SameDescriptorParams(defaults, changed)) << keys[k];
  }
}

TEST(Descriptor, KindsHaveTheirSizesAndDocumentedBlockSums) {
  Cloud cloud = CylinderFront(0.033, 0.2, 1.0, 30, 160, 40);
  Cloud cap = CylinderFront(0.015, 0.02, 0.99, 230, 230, 230);  // a white cap: achromatic
  cloud += cap;
  const DescriptorParts parts = ComputeDescriptorParts(cloud);
  const Eigen::VectorXf cvfh = AssembleDescriptor(parts, DescriptorKind::kCvfh);
  const Eigen::VectorXf raw = AssembleDescriptor(parts, DescriptorKind::kColorCvfh);
  const Eigen::VectorXf norm = AssembleDescriptor(parts, DescriptorKind::kColorCvfhNorm);
  EXPECT_EQ(cvfh.size(), 308);
  EXPECT_EQ(raw.size(), 500);
  EXPECT_EQ(norm.size(), 500);
  EXPECT_EQ(DescriptorSize(DescriptorKind::kColorCvfhNorm), kHsvBins + kCvfhBins);
  // Raw: [HSV counts | CVFH counts].
  EXPECT_TRUE(raw.head(kHsvBins).isApprox(parts.hsv));
  EXPECT_TRUE(raw.tail(kCvfhBins).isApprox(parts.cvfh));
  // Normalised: S, V and each CVFH block sum to 1; H to the chromatic fraction.
  const float chromatic = static_cast<float>(cloud.size() - cap.size()) / cloud.size();
  EXPECT_NEAR(norm.head(kHueBins).sum(), chromatic, kTol);
  EXPECT_NEAR(norm.segment(kHueBins, kSaturationBins).sum(), 1.0f, kTol);
  EXPECT_NEAR(norm.segment(kHueBins + kSaturationBins, kValueBins).sum(), 1.0f, kTol);
  for (const auto& [first, size] : kCvfhBlocks) {
    EXPECT_NEAR(norm.segment(kHsvBins + first, size).sum(), 1.0f, kTol);
    EXPECT_NEAR(cvfh.segment(first, size).sum(), 1.0f, kTol);
  }
  EXPECT_TRUE(norm.allFinite() && raw.allFinite() && cvfh.allFinite());
}

TEST(Descriptor, Deterministic) {
  const Cloud cloud = SphereFront(0.04, 1.1, 250, 140, 0);
  const DescriptorParts a = ComputeDescriptorParts(cloud), b = ComputeDescriptorParts(cloud);
  EXPECT_TRUE(a.hsv.isApprox(b.hsv, 0.0f));
  EXPECT_TRUE(a.cvfh.isApprox(b.cvfh, 0.0f));
}

TEST(Descriptor, UnknownNameIsAClearError) {
  EXPECT_EQ(ParseDescriptorKind("color-cvfh-norm"), DescriptorKind::kColorCvfhNorm);
  try {
    ParseDescriptorKind("vfh");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown descriptor 'vfh' (expected cvfh, color-cvfh or color-cvfh-norm)");
  }
}

// CVFH's pair features come from perception/pcl_instantiations.cc, written to PCL's arithmetic: here
// equal, to the bit, to what Debian's libpcl_features 1.13 gave for the same pairs (printed with %a by a
// program linked against it, 2026-12-07): both choices of the source point and both degenerate pairs.
TEST(PairFeatures, EqualPclsLibraryToTheBit) {
  struct Pair {
    Eigen::Vector4f p1, n1, p2, n2;
    bool ok;
    float f1, f2, f3, f4;
  };
  const Pair pairs[] = {
      {{0.1f, 0.2f, 0.7f, 1},
       {0.f, 0.6f, -0.8f, 0},
       {0.13f, 0.17f, 0.72f, 1},
       {0.48f, 0.6f, -0.64f, 0},
       true,
       0x1.c21302p-2f,
       0x1.11d194p-2f,
       -0x1.7323dap-1f,
       0x1.803d2ep-5f},
      {{0.1f, 0.2f, 0.7f, 1},
       {0.36f, 0.48f, -0.8f, 0},
       {0.102f, 0.23f, 0.69f, 1},
       {0.f, 0.f, -1.f, 0},
       true,
       -0x1.d2ab1ap-2f,
       0x1.d10b06p-2f,
       0x1.759612p-1f,
       0x1.039244p-5f},
      // The second point's normal makes the smaller angle with the line: the pair is taken the other way.
      {{-0.05f, 0.01f, 0.9f, 1},
       {0.f, 0.f, -1.f, 0},
       {-0.02f, 0.04f, 0.88f, 1},
       {0.f, 0.8f, -0.6f, 0},
       true,
       0x1.6a564ap-4f,
       0x1.98b15ap-1f,
       -0x1.88f8b6p-1f,
       0x1.803d22p-5f},
      {{0.1f, 0.2f, 0.7f, 1}, {0.f, 0.6f, -0.8f, 0}, {0.1f, 0.2f, 0.7f, 1}, {0.f, 0.6f, -0.8f, 0}, false, 0, 0, 0, 0},
      {{0.f, 0.f, 0.5f, 1}, {0.f, 0.f, -1.f, 0}, {0.f, 0.f, 0.6f, 1}, {0.f, 0.f, -1.f, 0}, false, 0, 0, 0, 0},
  };
  for (const Pair& p : pairs) {
    float f1 = -1, f2 = -1, f3 = -1, f4 = -1;
    EXPECT_EQ(pcl::computePairFeatures(p.p1, p.n1, p.p2, p.n2, f1, f2, f3, f4), p.ok);
    EXPECT_EQ(f1, p.f1);
    EXPECT_EQ(f2, p.f2);
    EXPECT_EQ(f3, p.f3);
    EXPECT_EQ(f4, p.f4);
  }
}

}  // namespace
}  // namespace sortcell::perception
