#include "assets/triangle_mesh.h"

namespace sortcell::assets {

TriangleMesh TriangleMesh::Transformed(const Eigen::Isometry3d& X) const {
  TriangleMesh out = *this;
  for (auto& v : out.vertices) v = X * v;
  for (auto& n : out.normals) n = X.linear() * n;
  return out;
}

TriangleMesh TriangleMesh::Scaled(const Eigen::Vector3d& s) const {
  TriangleMesh out = *this;
  for (auto& v : out.vertices) v = v.cwiseProduct(s);
  // A non-uniform scale turns normals by the inverse scale.
  for (auto& n : out.normals) n = n.cwiseQuotient(s).normalized();
  return out;
}

}  // namespace sortcell::assets
