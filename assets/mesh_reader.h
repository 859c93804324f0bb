#pragma once
/// @file
/// Reading a user's mesh file (OBJ or STL, ASCII or binary) into one TriangleMesh, with Open Asset
/// Import Library (assimp): it reads both formats and many more, triangulates polygons and unifies
/// OBJ's separate position/UV/normal indices into vertices a renderer can use.

#include <filesystem>
#include <string>

#include "assets/triangle_mesh.h"

namespace sortcell::assets {

/// The mesh in `file`: all of its meshes joined, vertices shared where position, normal and UV agree,
/// UVs upright (v = 0 at the image's top). The material's diffuse texture file, if it names one,
/// is returned in `texture` (as written in the file, relative to the mesh's folder).
/// @throws std::invalid_argument "mesh '<file>': <what>" for a missing or unreadable file, a format
///         assimp does not read, no triangles, or non-finite vertices.
TriangleMesh ReadMesh(const std::filesystem::path& file, std::string* texture = nullptr);

/// The same from bytes in memory; `extension_hint` ("obj", "stl") picks the format, `name` names the
/// source in errors. For tests and fuzzing.
TriangleMesh ReadMeshFromMemory(const std::string& bytes, const std::string& extension_hint, const std::string& name,
                                std::string* texture = nullptr);

}  // namespace sortcell::assets
