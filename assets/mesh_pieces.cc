#include "assets/mesh_pieces.h"

#include <map>
#include <numeric>
#include <tuple>

namespace sortcell::assets {
namespace {

// Union-find over welded vertices (by hand: a dozen lines; Boost's disjoint sets would add a
// dependency for them).
class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(int a, int b) { parent_[Find(a)] = Find(b); }

 private:
  std::vector<int> parent_;
};

// Each vertex's welded index: the first vertex at exactly its position.
std::vector<int> WeldedIndex(const TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, int> first;
  std::vector<int> welded(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& v = mesh.vertices[i];
    welded[i] = first.emplace(std::make_tuple(v.x(), v.y(), v.z()), static_cast<int>(i)).first->second;
  }
  return welded;
}

}  // namespace

std::vector<TriangleMesh> ConnectedPieces(const TriangleMesh& mesh) {
  const std::vector<int> welded = WeldedIndex(mesh);
  DisjointSets sets(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    sets.Join(welded[t[0]], welded[t[1]]);
    sets.Join(welded[t[0]], welded[t[2]]);
  }
  std::map<int, size_t> piece_of_root;
  std::vector<TriangleMesh> pieces;
  std::vector<std::map<int, int>> local_index;
  for (const auto& t : mesh.triangles) {
    const int root = sets.Find(welded[t[0]]);
    const auto [it, added] = piece_of_root.emplace(root, pieces.size());
    if (added) {
      pieces.emplace_back();
      local_index.emplace_back();
    }
    TriangleMesh& piece = pieces[it->second];
    Eigen::Vector3i local;
    for (int k = 0; k < 3; ++k) {
      const int w = welded[t[k]];
      const auto [slot, is_new] = local_index[it->second].emplace(w, static_cast<int>(piece.vertices.size()));
      if (is_new) piece.vertices.push_back(mesh.vertices[w]);
      local[k] = slot->second;
    }
    piece.triangles.push_back(local);
  }
  return pieces;
}

}  // namespace sortcell::assets
