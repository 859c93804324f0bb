#include "assets/mass_properties.h"

#include <libqhullcpp/Qhull.h>
#include <libqhullcpp/QhullError.h>
#include <libqhullcpp/QhullFacet.h>
#include <libqhullcpp/QhullFacetList.h>
#include <libqhullcpp/QhullVertexSet.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <stdexcept>

namespace sortcell::assets {

// Written here: the integrals are a few lines over the mesh (no Debian library offers them for a bare
// triangle list without building its own mesh type). Each triangle (a, b, c) with the origin spans a
// tetrahedron of signed volume det/6, det = a . (b x c); its second moment integral of x x^T is
// det/120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
MassProperties MassPropertiesOf(const TriangleMesh& closed) {
  double six_volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // 24 x the first moment
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // 120 x the second moment
  for (const auto& t : closed.triangles) {
    const Eigen::Vector3d& a = closed.vertices[t[0]];
    const Eigen::Vector3d& b = closed.vertices[t[1]];
    const Eigen::Vector3d& c = closed.vertices[t[2]];
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d s = a + b + c;
    six_volume += det;
    first += det * s;
    second += det * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  const double sign = six_volume < 0 ? -1 : 1;  // an inward-oriented mesh
  MassProperties m;
  m.volume = sign * six_volume / 6;
  if (m.volume <= 0) return m;
  m.centroid = sign * first / 24 / m.volume;
  const Eigen::Matrix3d covariance = sign * second / 120 - m.volume * m.centroid * m.centroid.transpose();
  m.inertia = covariance.trace() * Eigen::Matrix3d::Identity() - covariance;
  return m;
}

bool IsClosedAndOriented(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1) return false;
    }
  }
  for (const auto& [edge, count] : directed) {
    if (!directed.count({edge.second, edge.first})) return false;
  }
  return !mesh.triangles.empty();
}

MassProperties Combined(const std::vector<MassProperties>& parts) {
  MassProperties total;
  for (const auto& p : parts) {
    total.volume += p.volume;
    total.centroid += p.volume * p.centroid;
  }
  if (total.volume <= 0) return total;
  total.centroid /= total.volume;
  for (const auto& p : parts) {  // parallel axis theorem
    const Eigen::Vector3d d = p.centroid - total.centroid;
    total.inertia += p.inertia + p.volume * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return total;
}

TriangleMesh ConvexHull(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4)
    throw std::invalid_argument("a convex hull needs 4 points, got " + std::to_string(points.size()));
  std::vector<double> coordinates;
  coordinates.reserve(3 * points.size());
  for (const auto& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  orgQhull::Qhull qhull;
  try {
    qhull.runQhull("", 3, static_cast<int>(points.size()), coordinates.data(), "Qt");
  } catch (const orgQhull::QhullError& e) {
    throw std::invalid_argument("the points span no volume (qhull: " + std::string(e.what()).substr(0, 80) + ")");
  }
  TriangleMesh hull;
  std::vector<int> index_of(points.size(), -1);
  for (const orgQhull::QhullFacet& facet : qhull.facetList()) {
    const orgQhull::QhullVertexSet corners = facet.vertices();
    if (corners.size() != 3) continue;
    Eigen::Vector3i t;
    for (int k = 0; k < 3; ++k) {
      const int id = corners[k].point().id();
      if (index_of[id] < 0) {
        index_of[id] = static_cast<int>(hull.vertices.size());
        hull.vertices.push_back(points[id]);
      }
      t[k] = index_of[id];
    }
    const Eigen::Vector3d& a = hull.vertices[t[0]];
    const Eigen::Vector3d normal = (hull.vertices[t[1]] - a).cross(hull.vertices[t[2]] - a);
    const double* plane = facet.hyperplane().coordinates();
    if (normal.dot(Eigen::Vector3d(plane[0], plane[1], plane[2])) < 0) std::swap(t[1], t[2]);
    hull.triangles.push_back(t);
  }
  return hull;
}

double MinimumWidth(const std::vector<Eigen::Vector2d>& points) {
  std::vector<cv::Point2f> in;
  for (const auto& p : points) in.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  if (in.size() < 3) return 0;
  std::vector<cv::Point2f> hull;
  cv::convexHull(in, hull);
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < hull.size(); ++i) {  // the narrowest strip lies flush with an edge
    const Eigen::Vector2d a(hull[i].x, hull[i].y);
    const Eigen::Vector2d b(hull[(i + 1) % hull.size()].x, hull[(i + 1) % hull.size()].y);
    const Eigen::Vector2d edge = b - a;
    if (edge.norm() == 0) continue;
    const Eigen::Vector2d normal = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
    double width = 0;
    for (const auto& p : hull) width = std::max(width, std::abs(normal.dot(Eigen::Vector2d(p.x, p.y) - a)));
    best = std::min(best, width);
  }
  return std::isfinite(best) ? best : 0;
}

}  // namespace sortcell::assets
