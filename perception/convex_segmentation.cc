#include "perception/convex_segmentation.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <pcl/common/angles.h>
#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>
// LCCP's template bodies: PCL 1.13 does not instantiate it for every point type.
#include <pcl/segmentation/impl/lccp_segmentation.hpp>

#include <opencv2/imgproc.hpp>

#include "perception/normal_estimation.h"
#include "perception/supervoxel_normals.h"
#include "perception/supervoxels.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace sortcell::perception {
namespace {

// A cluster's volume over the plane: its footprint (the convex hull of its voxels projected onto the
// plane, in plane coordinates), its top and bottom (the largest and smallest height above the plane).
struct Volume {
  std::vector<cv::Point2f> hull;
  cv::Point2f lowest, highest;  // The footprint's bounding box.
  float top = 0, bottom = 0;
  /// The circle the footprint lies on if the cluster is a round wall (a cup's, a bowl's seen from
  /// outside): the geometric least-squares circle through its voxels' footprint, and their median distance
  /// from it (small for a round wall, large for a box's or a lying bottle's footprint).
  cv::Point2f circle_centre;
  float circle_radius = 0, circle_residual = 0;
};

struct PlaneFrame {
  Eigen::Vector3f n, u, v;
  float d = 0;
  cv::Point2f Project(const PointT& p) const {
    const Eigen::Vector3f x = p.getVector3fMap();
    return {u.dot(x), v.dot(x)};
  }
  float Height(const PointT& p) const { return n.dot(p.getVector3fMap()) + d; }
};

PlaneFrame MakePlaneFrame(const Eigen::Vector4d& plane_C) {
  PlaneFrame f;
  f.n = plane_C.head<3>().cast<float>().normalized();
  f.d = static_cast<float>(plane_C[3] / plane_C.head<3>().norm());
  f.u = f.n.unitOrthogonal();
  f.v = f.n.cross(f.u);
  return f;
}

// The circle through `points` that minimises the squared distances from it (geometric least squares),
// and the points' median distance from it. Kasa's algebraic fit (x^2 + y^2 + D x + E y + F = 0, linear
// in D, E, F) starts it; a few Gauss-Newton steps then remove Kasa's bias towards small circles on a
// short arc (the near side of a cup: 32 mm instead of its 38). OpenCV fits ellipses, not circles.
void FitFootprintCircle(const std::vector<cv::Point2f>& points, Volume& volume) {
  if (points.size() < 3) return;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += Eigen::Vector2d(p.x, p.y);
  mean /= static_cast<double>(points.size());  // Centred: better conditioned.
  std::vector<Eigen::Vector2d> q;
  for (const auto& p : points) q.push_back(Eigen::Vector2d(p.x, p.y) - mean);
  Eigen::MatrixX3d a(q.size(), 3);
  Eigen::VectorXd b(q.size());
  for (size_t i = 0; i < q.size(); ++i) {
    a.row(i) << q[i].x(), q[i].y(), 1;
    b[i] = -q[i].squaredNorm();
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  Eigen::Vector2d centre = -def.head<2>() / 2;
  double r2 = centre.squaredNorm() - def[2];
  if (!def.allFinite() || r2 <= 0) return;
  double radius = std::sqrt(r2);
  for (int step = 0; step < 10; ++step) {  // Residual d_i - r; Jacobian rows (-(q_i - c) / d_i, -1).
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const auto& p : q) {
      const double d = (p - centre).norm();
      if (d <= 0) continue;
      const Eigen::Vector3d j(-(p - centre).x() / d, -(p - centre).y() / d, -1);
      jtj += j * j.transpose();
      jtr += j * (d - radius);
    }
    const Eigen::Vector3d delta = jtj.ldlt().solve(-jtr);
    if (!delta.allFinite()) break;
    centre += delta.head<2>();
    radius += delta[2];
    if (delta.norm() < 1e-6) break;
  }
  if (!(radius > 0) || !centre.allFinite()) return;
  volume.circle_centre =
      cv::Point2f(static_cast<float>(centre.x() + mean.x()), static_cast<float>(centre.y() + mean.y()));
  volume.circle_radius = static_cast<float>(radius);
  std::vector<float> residuals;
  for (const auto& p : q) residuals.push_back(static_cast<float>(std::abs((p - centre).norm() - radius)));
  std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
  volume.circle_residual = residuals[residuals.size() / 2];
}

Volume VolumeOf(const Cloud& voxels, const pcl::PointIndices& cluster, const PlaneFrame& frame) {
  std::vector<cv::Point2f> footprint;
  Volume volume;
  volume.top = -1e9f;
  volume.bottom = 1e9f;
  for (int i : cluster.indices) {
    footprint.push_back(frame.Project(voxels[i]));
    volume.top = std::max(volume.top, frame.Height(voxels[i]));
    volume.bottom = std::min(volume.bottom, frame.Height(voxels[i]));
  }
  cv::convexHull(footprint, volume.hull);
  volume.lowest = volume.highest = footprint.empty() ? cv::Point2f() : footprint.front();
  for (const auto& p : footprint) {
    volume.lowest = cv::Point2f(std::min(volume.lowest.x, p.x), std::min(volume.lowest.y, p.y));
    volume.highest = cv::Point2f(std::max(volume.highest.x, p.x), std::max(volume.highest.y, p.y));
  }
  FitFootprintCircle(footprint, volume);
  return volume;
}

// The largest distance between two points of a convex footprint.
float Diameter(const std::vector<cv::Point2f>& hull) {
  float diameter = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    for (size_t j = i + 1; j < hull.size(); ++j)
      diameter = std::max(diameter, static_cast<float>(cv::norm(hull[i] - hull[j])));
  }
  return diameter;
}

// Whether `inner` is the inside of the hollow object whose outer wall is `wall`, seen over the rim. The
// wall stands on the plane and is round: its footprint lies close to the circle fitted through it (a
// cup's, a bowl's, a pot's), and that circle is no wider than the footprint allows (the near side of a
// round wall spans most of a half circle; a flat face fits a circle of any size). The inside lies beyond
// the wall from the camera, reaches up to the rim (its far side) but not above, and lies within the
// rim's circle. A neighbour seen beyond the rim stands outside that circle.
bool IsInsideOfHollow(const Volume& inner, const Volume& wall, const ConvexClusteringParams& params) {
  if (wall.hull.size() < 3 || inner.hull.empty() || wall.bottom > params.hollow_lift_m) return false;
  if (inner.top > wall.top + params.top_tolerance_m || inner.top < wall.top - params.rim_tolerance_m) return false;
  // Seen over the near rim, the inside lies beyond the wall from the camera (at the plane frame's origin).
  const auto range = [](const std::vector<cv::Point2f>& hull) {
    cv::Point2f c(0, 0);
    for (const auto& p : hull) c += p;
    return cv::norm(c / static_cast<float>(hull.size()));
  };
  if (range(inner.hull) <= range(wall.hull)) return false;
  if (wall.circle_radius <= 0 || wall.circle_residual > params.round_wall_residual * wall.circle_radius) return false;
  if (wall.circle_radius > params.round_wall_radius_factor * Diameter(wall.hull)) return false;
  return std::all_of(inner.hull.begin(), inner.hull.end(), [&](const cv::Point2f& p) {
    return cv::norm(p - wall.circle_centre) <= wall.circle_radius + params.rim_tolerance_m;
  });
}

// Whether `piece` (of `piece_voxels`) is the top of the object `base` (of `base_voxels`) stands for, cut
// off at a concave crease of its own (a bottle's neck and cap over its shoulder): much smaller, it
// begins at the base's top, and its footprint's middle lies over the base's footprint. An object
// stacked on another is about as large as it (boxes on boxes) and stays apart.
bool IsCapOf(const Volume& piece, size_t piece_voxels, const Volume& base, size_t base_voxels,
             const ConvexClusteringParams& params) {
  if (base.hull.size() < 3 || piece.hull.empty()) return false;
  if (piece_voxels > params.cap_fraction * base_voxels) return false;
  if (piece.bottom < base.top - params.cap_overlap_m || piece.bottom > base.top + params.top_tolerance_m) return false;
  cv::Point2f middle(0, 0);
  for (const auto& p : piece.hull) middle += p;
  return cv::pointPolygonTest(base.hull, middle / static_cast<float>(piece.hull.size()), false) >= 0;
}

// Whether `piece` is the end of a long object lying on its side (`base`: a bottle's neck and cap, cut
// off at the shoulder's crease): much smaller, no higher, and its middle on the base's long axis just
// beyond the base's end.
bool IsNeckOf(const Volume& piece, size_t piece_voxels, const Volume& base, size_t base_voxels,
              const ConvexClusteringParams& params) {
  if (base.hull.size() < 3 || piece.hull.empty()) return false;
  if (piece_voxels > params.cap_fraction * base_voxels || piece.top > base.top + params.top_tolerance_m) return false;
  const cv::RotatedRect box = cv::minAreaRect(base.hull);
  const float length = std::max(box.size.width, box.size.height), width = std::min(box.size.width, box.size.height);
  if (length < params.lying_elongation * width) return false;
  const float angle = static_cast<float>(box.angle * M_PI / 180) +
                      (box.size.width >= box.size.height ? 0.0f : static_cast<float>(M_PI / 2));
  const cv::Point2f along(std::cos(angle), std::sin(angle));
  cv::Point2f middle(0, 0);
  for (const auto& p : piece.hull) middle += p;
  const cv::Point2f r = middle / static_cast<float>(piece.hull.size()) - box.center;
  const float u = std::abs(r.dot(along)), v = std::abs(r.x * along.y - r.y * along.x);
  return v <= 0.5f * width && u >= 0.5f * length - params.top_tolerance_m && u <= 0.5f * length + params.neck_length_m;
}

bool BoxesOverlap(const Volume& a, const Volume& b) {
  return a.lowest.x <= b.highest.x && b.lowest.x <= a.highest.x && a.lowest.y <= b.highest.y &&
         b.lowest.y <= a.highest.y;
}

// Joins each cluster that lies mostly inside a larger one's volume to it (smallest first).
void JoinPiecesInsideOthers(const Cloud& voxels, const PlaneFrame& frame, const ConvexClusteringParams& params,
                            std::vector<pcl::PointIndices>& clusters) {
  std::vector<Volume> volumes;
  for (const auto& c : clusters) volumes.push_back(VolumeOf(voxels, c, frame));
  std::vector<bool> joined(clusters.size(), false);
  for (size_t a = clusters.size();
       a-- > 1;) {  // Smallest first (clusters are sorted largest first); a piece joins a larger one.
    size_t best = a;
    double best_fraction = params.inside_fraction;
    for (size_t b = 0; b < a; ++b) {
      if (IsInsideOfHollow(volumes[a], volumes[b], params) || IsInsideOfHollow(volumes[b], volumes[a], params) ||
          IsCapOf(volumes[a], clusters[a].indices.size(), volumes[b], clusters[b].indices.size(), params) ||
          IsNeckOf(volumes[a], clusters[a].indices.size(), volumes[b], clusters[b].indices.size(), params)) {
        best = b;
        break;
      }
      // No voxel of a lies inside b's hull if their footprints' boxes are apart (most pairs of a frame).
      if (volumes[b].hull.size() < 3 || !BoxesOverlap(volumes[a], volumes[b])) continue;
      int inside = 0;
      for (int i : clusters[a].indices) {
        inside += frame.Height(voxels[i]) <= volumes[b].top + params.top_tolerance_m &&
                  cv::pointPolygonTest(volumes[b].hull, frame.Project(voxels[i]), false) >= 0;
      }
      const double fraction = static_cast<double>(inside) / clusters[a].indices.size();
      if (fraction >= best_fraction) best_fraction = fraction, best = b;
    }
    if (best == a) continue;
    clusters[best].indices.insert(clusters[best].indices.end(), clusters[a].indices.begin(), clusters[a].indices.end());
    joined[a] = true;
  }
  std::vector<pcl::PointIndices> kept;
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (!joined[c]) kept.push_back(std::move(clusters[c]));
  }
  clusters = std::move(kept);
}

using SupervoxelMap = std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr>;
using Adjacency = std::multimap<std::uint32_t, std::uint32_t>;

// CIE L*a*b* colour of each supervoxel's mean colour (Euclidean distance ~ perceived difference).
std::map<std::uint32_t, Eigen::Vector3f> LabColours(const SupervoxelMap& supervoxels) {
  cv::Mat rgb(static_cast<int>(supervoxels.size()), 1, CV_32FC3);
  int row = 0;
  for (const auto& [label, sv] : supervoxels) {
    rgb.at<cv::Vec3f>(row++) = cv::Vec3f(sv->centroid_.r, sv->centroid_.g, sv->centroid_.b) / 255.0f;
  }
  cv::Mat lab;
  cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
  std::map<std::uint32_t, Eigen::Vector3f> colours;
  row = 0;
  for (const auto& [label, sv] : supervoxels) {
    const cv::Vec3f c = lab.at<cv::Vec3f>(row++);
    colours[label] = {c[0], c[1], c[2]};
  }
  return colours;
}

// LCCP's convexity test (Stein et al. 2014, eq. 3): the connection a-b is concave when the normals
// open towards each other; then its concavity is the angle between the normals (else 0).
double ConcavityDeg(const pcl::Supervoxel<PointT>& a, const pcl::Supervoxel<PointT>& b) {
  const Eigen::Vector3f n_a = a.normal_.getNormalVector3fMap().normalized();
  const Eigen::Vector3f n_b = b.normal_.getNormalVector3fMap().normalized();
  const Eigen::Vector3f b_to_a = (a.centroid_.getVector3fMap() - b.centroid_.getVector3fMap()).normalized();
  const auto angle = [](const Eigen::Vector3f& x, const Eigen::Vector3f& y) {
    return std::acos(std::clamp(x.dot(y), -1.0f, 1.0f));
  };
  if (angle(b_to_a, n_a) - angle(b_to_a, n_b) <= 0) return 0;
  return pcl::rad2deg(angle(n_a, n_b));
}

// Removes the connections between differently coloured supervoxels that are even slightly concave:
// two touching objects of different colour come apart where their surfaces meet at a shallow crease,
// while a label or print on one object (a colour edge across a flat or convex surface) stays joined.
void CutColourCreases(const SupervoxelMap& supervoxels, const ConvexClusteringParams& params, Adjacency& adjacency) {
  const std::map<std::uint32_t, Eigen::Vector3f> lab = LabColours(supervoxels);
  for (auto it = adjacency.begin(); it != adjacency.end();) {
    const auto a = supervoxels.find(it->first), b = supervoxels.find(it->second);
    const bool cut = a != supervoxels.end() && b != supervoxels.end() &&
                     (lab.at(it->first) - lab.at(it->second)).norm() > params.colour_edge_delta_e &&
                     ConcavityDeg(*a->second, *b->second) > params.colour_edge_concavity_deg;
    it = cut ? adjacency.erase(it) : std::next(it);
  }
}

// Segments of at most this many supervoxels join their largest neighbouring segment (LCCP's noise filter).
constexpr size_t kSmallSegmentSupervoxels = 3;

using SegmentOf = std::map<std::uint32_t, std::uint32_t>;  // Supervoxel label -> its segment's name.

// Each segment renamed after its smallest supervoxel (supervoxel labels start at 1: never 0, none).
void NameBySmallestSupervoxel(SegmentOf& segment_of) {
  std::map<std::uint32_t, std::uint32_t> name_of;
  for (const auto& [sv, seg] : segment_of) name_of.try_emplace(seg, sv);  // Supervoxels ascend.
  for (auto& [sv, seg] : segment_of) seg = name_of[seg];
}

// The segments each segment touches across the (cut) supervoxel adjacency.
std::map<std::uint32_t, std::set<std::uint32_t>> SegmentNeighbours(const SegmentOf& segment_of,
                                                                   const Adjacency& adjacency) {
  std::map<std::uint32_t, std::set<std::uint32_t>> neighbours;
  for (const auto& [a, b] : adjacency) {
    const auto sa = segment_of.find(a), sb = segment_of.find(b);
    if (sa == segment_of.end() || sb == segment_of.end() || sa->second == sb->second) continue;
    neighbours[sa->second].insert(sb->second);
    neighbours[sb->second].insert(sa->second);
  }
  return neighbours;
}

// One pass of LCCP's noise filter, in name order: a small segment joins its largest neighbour of at
// least its own size (ties: the lowest name), unless that one has joined another in this pass. A
// segment grows as others join it (LCCP moves their supervoxels at once) and joins none itself in that
// pass. Returns each joining segment and the one it joins.
std::map<std::uint32_t, std::uint32_t> PlanJoins(const SegmentOf& segment_of, const Adjacency& adjacency) {
  std::map<std::uint32_t, size_t> size;
  for (const auto& [sv, seg] : segment_of) ++size[seg];
  const auto neighbours = SegmentNeighbours(segment_of, adjacency);
  std::map<std::uint32_t, std::uint32_t> joins;
  std::set<std::uint32_t> joined_by_others;
  for (const auto& [seg, n] : size) {
    const auto near = neighbours.find(seg);
    if (n > kSmallSegmentSupervoxels || near == neighbours.end() || joined_by_others.count(seg)) continue;
    std::uint32_t largest = seg;
    for (std::uint32_t other : near->second) {
      if (size.at(other) < n) continue;
      if (largest == seg || size.at(other) > size.at(largest)) largest = other;
    }
    if (largest == seg || joins.count(largest)) continue;
    joins[seg] = largest;
    joined_by_others.insert(largest);
    size[largest] += n;
  }
  return joins;
}

// Each supervoxel's segment, named after the segment's smallest supervoxel. LCCP numbers its segments,
// and runs its own small-segment merge, in the order of its graph's vertices, which boost keeps in a
// set of pointers: the order of heap addresses, so it changes from run to run (ASLR). The supervoxels
// and their adjacency do not; segments named after them, merged in that order, are the same every run.
SegmentOf CanonicalSegments(SegmentOf segment_of, const Adjacency& adjacency) {
  NameBySmallestSupervoxel(segment_of);
  // Passes until no small segment can join another (each pass that joins leaves fewer segments).
  for (auto joins = PlanJoins(segment_of, adjacency); !joins.empty(); joins = PlanJoins(segment_of, adjacency)) {
    for (auto& [sv, seg] : segment_of) {
      const auto join = joins.find(seg);
      if (join != joins.end()) seg = join->second;  // No chains: a segment joined this pass joins none.
    }
  }
  NameBySmallestSupervoxel(segment_of);
  return segment_of;
}

// The supervoxels of `voxels`, computed here where that reproduces PCL's, else by PCL.
SupervoxelGraph SupervoxelsOf(const Cloud::Ptr& voxels, const ConvexClusteringParams& params) {
  SupervoxelSettings settings;
  settings.voxel_m = static_cast<float>(params.voxel_m);
  settings.seed_m = static_cast<float>(params.seed_m);
  settings.colour_importance = static_cast<float>(params.colour_importance);
  settings.spatial_importance = 1.0f;
  settings.normal_importance = static_cast<float>(params.normal_importance);
  if (params.own_voxel_normals && params.own_supervoxels) {
    std::optional<SupervoxelGraph> graph = ExtractSupervoxels(*voxels, settings);
    if (graph) return *std::move(graph);
  }
  pcl::PointCloud<pcl::Normal>::Ptr normals;
  if (params.own_voxel_normals) {  // The voxel normals PCL would compute, computed faster.
    normals = std::make_shared<pcl::PointCloud<pcl::Normal>>(SupervoxelVoxelNormals(*voxels, settings.voxel_m));
  }
  return PclSupervoxels(voxels, normals, settings);
}

// Voxel i's segment (0: none), in the input's order; segments named as CanonicalSegments names them.
std::vector<std::uint32_t> LccpLabels(const Cloud::Ptr& voxels, const ConvexClusteringParams& params) {
  SupervoxelGraph graph = SupervoxelsOf(voxels, params);
  CutColourCreases(graph.supervoxels, params, graph.adjacency);

  pcl::LCCPSegmentation<PointT> lccp;
  lccp.setConcavityToleranceThreshold(static_cast<float>(params.concavity_deg));
  lccp.setSanityCheck(true);
  lccp.setSmoothnessCheck(true, static_cast<float>(params.voxel_m), static_cast<float>(params.seed_m), 0.1f);
  lccp.setKFactor(0);
  lccp.setMinSegmentSize(0);  // Merged in CanonicalSegments instead.
  lccp.setInputSupervoxels(graph.supervoxels, graph.adjacency);
  lccp.segment();
  SegmentOf lccp_segment_of;
  lccp.getSupervoxelToSegmentMap(lccp_segment_of);
  const SegmentOf segment_of = CanonicalSegments(std::move(lccp_segment_of), graph.adjacency);
  std::vector<std::uint32_t> labels(voxels->size(), 0);
  for (size_t i = 0; i < graph.label_of_point.size() && i < labels.size(); ++i) {
    const auto segment = segment_of.find(graph.label_of_point[i]);
    if (segment != segment_of.end()) labels[i] = segment->second;
  }
  return labels;
}

// Which voxels lie in a concave crease, seen at the voxels' own resolution: at least
// crease_rising_neighbours of their neighbours rise above their tangent plane by more than
// crease_height_m and crease_deg. A flat or convex surface has none (a box's edge, a print, noise of a
// millimetre); the inside of a cup rises too gently (3 mm over 10 mm at its 38 mm radius, seen from inside).
std::vector<bool> CreaseVoxels(const Cloud& voxels, const NeighbourLists& neighbours,
                               const pcl::PointCloud<pcl::Normal>& normals, const ConvexClusteringParams& params) {
  const float sin_crease = static_cast<float>(std::sin(pcl::deg2rad(params.crease_deg)));
  const float min_height = static_cast<float>(params.crease_height_m);
  std::vector<bool> crease(voxels.size(), false);
  for (size_t i = 0; i < voxels.size(); ++i) {
    const Eigen::Vector3f n = normals[i].getNormalVector3fMap();
    if (!n.allFinite()) continue;
    int rising = 0;
    for (int j : neighbours.Of(i)) {
      const Eigen::Vector3f d = voxels[j].getVector3fMap() - voxels[i].getVector3fMap();
      const float height = n.dot(d);
      rising += height > min_height && height > sin_crease * d.norm();
    }
    crease[i] = rising >= params.crease_rising_neighbours;
  }
  return crease;
}

// The connected parts of each segment's voxels outside creases (neighbours within split_link_m): the
// part of each voxel (-1: a crease voxel or none), and each part's size.
struct Parts {
  std::vector<int> of_voxel;
  std::vector<int> size;
};

Parts PartsOutsideCreases(const Cloud& voxels, const NeighbourLists& neighbours, const std::vector<bool>& crease,
                          const std::vector<std::uint32_t>& labels, const ConvexClusteringParams& params) {
  const float link2 = static_cast<float>(params.split_link_m * params.split_link_m);
  Parts parts;
  parts.of_voxel.assign(voxels.size(), -1);
  std::vector<int> stack;
  for (size_t seed = 0; seed < voxels.size(); ++seed) {
    if (crease[seed] || labels[seed] == 0 || parts.of_voxel[seed] >= 0) continue;
    const int id = static_cast<int>(parts.size.size());
    parts.size.push_back(0);
    parts.of_voxel[seed] = id;
    stack.assign(1, static_cast<int>(seed));
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      ++parts.size[id];
      for (int j : neighbours.Of(i)) {
        if (crease[j] || parts.of_voxel[j] >= 0 || labels[j] != labels[i] ||
            (voxels[j].getVector3fMap() - voxels[i].getVector3fMap()).squaredNorm() > link2)
          continue;
        parts.of_voxel[j] = id;
        stack.push_back(j);
      }
    }
  }
  return parts;
}

// Each segment with two or more large parts (split_min_voxels) becomes one segment per large part,
// named after the existing ones; its other voxels (creases, small parts) join the nearest large part,
// grown breadth first over the segment.
void SplitSegmentsWithLargeParts(const NeighbourLists& neighbours, const Parts& parts,
                                 const ConvexClusteringParams& params, std::vector<std::uint32_t>& labels) {
  const auto large = [&](size_t i) {
    return parts.of_voxel[i] >= 0 && parts.size[parts.of_voxel[i]] >= params.split_min_voxels;
  };
  std::map<std::uint32_t, std::set<int>> large_parts_of_segment;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (large(i)) large_parts_of_segment[labels[i]].insert(parts.of_voxel[i]);
  }
  std::vector<int> owner(labels.size(), -1);
  std::vector<int> frontier, next;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (large(i) && large_parts_of_segment[labels[i]].size() >= 2)
      owner[i] = parts.of_voxel[i], frontier.push_back(static_cast<int>(i));
  }
  while (!frontier.empty()) {
    next.clear();
    for (int i : frontier) {
      for (int j : neighbours.Of(i)) {
        if (owner[j] < 0 && labels[j] == labels[i]) owner[j] = owner[i], next.push_back(j);
      }
    }
    frontier.swap(next);
  }
  std::uint32_t next_name = 1 + *std::max_element(labels.begin(), labels.end());
  std::map<int, std::uint32_t> name_of_part;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (owner[i] < 0) continue;
    const auto [it, added] = name_of_part.try_emplace(owner[i], next_name);
    next_name += added;
    labels[i] = it->second;
  }
}

// Splits the segments `labels` of `voxels` at the concave creases their supervoxels straddled.
void SplitAtCreases(const Cloud& voxels, const ConvexClusteringParams& params, std::vector<std::uint32_t>& labels) {
  const Neighbourhoods around = GridNeighbourhoods(voxels, params.crease_radius_m);
  const NeighbourLists& neighbours = around.neighbours;
  const std::vector<bool> crease = CreaseVoxels(voxels, neighbours, around.normals, params);
  SplitSegmentsWithLargeParts(neighbours, PartsOutsideCreases(voxels, neighbours, crease, labels, params), params,
                              labels);
}

}  // namespace

std::vector<pcl::PointIndices> ConvexClusters(const Cloud::Ptr& voxels, const Eigen::Vector4d& plane_C,
                                              const ConvexClusteringParams& params) {
  if (voxels->empty()) return {};
  std::vector<std::uint32_t> labels = LccpLabels(voxels, params);
  if (params.split_at_creases) SplitAtCreases(*voxels, params, labels);
  std::map<std::uint32_t, pcl::PointIndices> by_label;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] != 0) by_label[labels[i]].indices.push_back(static_cast<int>(i));
  }
  std::vector<pcl::PointIndices> out;
  for (auto& [label, indices] : by_label) out.push_back(std::move(indices));
  const auto larger = [](const pcl::PointIndices& a, const pcl::PointIndices& b) {
    return a.indices.size() > b.indices.size();
  };
  // Stable: clusters of one size stay in the order of their names, so the order is the same every run.
  std::stable_sort(out.begin(), out.end(), larger);
  JoinPiecesInsideOthers(*voxels, MakePlaneFrame(plane_C), params, out);
  std::stable_sort(out.begin(), out.end(), larger);
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&params](const pcl::PointIndices& c) {
                             const int n = static_cast<int>(c.indices.size());
                             return n < params.min_cluster_voxels || n > params.max_cluster_voxels;
                           }),
            out.end());
  return out;
}

}  // namespace sortcell::perception
