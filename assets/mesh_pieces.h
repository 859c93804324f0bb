#pragma once
/// @file
/// A mesh's disconnected pieces. A convex decomposition is often shipped as one file holding its
/// convex parts side by side (V-HACD's output, e.g. the YCB objects' textured_vhacd.stl); MuJoCo
/// turns one mesh into one convex hull, so each part must become a mesh of its own.

#include <vector>

#include "assets/triangle_mesh.h"

namespace sortcell::assets {

/// The connected pieces of `mesh`, triangles joined where they share a vertex position (STL files
/// repeat each corner per triangle). Positions only: normals and UVs are dropped. Pieces come in the
/// order of their first triangle.
std::vector<TriangleMesh> ConnectedPieces(const TriangleMesh& mesh);

}  // namespace sortcell::assets
