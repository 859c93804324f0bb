#include "assets/mesh_reader.h"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <stdexcept>
#include <system_error>

namespace sortcell::assets {
namespace {

// Triangulated, identical vertices joined (OBJ's v/vt/vn triples become shared vertices), UVs
// flipped to the image's top-left origin (what MuJoCo's mesh texcoords use), degenerate triangles
// and lines/points dropped, and assimp's own consistency checks (indices in range and the like).
constexpr unsigned kPostProcess = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_FlipUVs |
                                  aiProcess_FindDegenerates | aiProcess_SortByPType | aiProcess_ValidateDataStructure;

[[noreturn]] void Fail(const std::string& name, const std::string& what) {
  throw std::invalid_argument("mesh '" + name + "': " + what);
}

bool Finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void Append(const aiMesh& mesh, const std::string& name, TriangleMesh& out) {
  if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;
  const int base = static_cast<int>(out.vertices.size());
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D& v = mesh.mVertices[i];
    if (!Finite(v)) Fail(name, "vertex " + std::to_string(i) + " is not a finite number");
    out.vertices.emplace_back(v.x, v.y, v.z);
  }
  for (unsigned i = 0; i < mesh.mNumFaces; ++i) {
    const aiFace& face = mesh.mFaces[i];
    if (face.mNumIndices != 3) continue;
    out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                               base + static_cast<int>(face.mIndices[2]));
  }
}

void AppendAttributes(const aiMesh& mesh, TriangleMesh& out) {
  if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D n = mesh.mNormals ? mesh.mNormals[i] : aiVector3D(0, 0, 1);
    out.normals.emplace_back(Finite(n) ? Eigen::Vector3d(n.x, n.y, n.z) : Eigen::Vector3d::UnitZ());
    const aiVector3D uv = mesh.mTextureCoords[0] ? mesh.mTextureCoords[0][i] : aiVector3D(0, 0, 0);
    out.uvs.emplace_back(Finite(uv) ? Eigen::Vector2d(uv.x, uv.y) : Eigen::Vector2d::Zero());
  }
}

std::string DiffuseTexture(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const unsigned index = scene.mMeshes[m]->mMaterialIndex;
    if (index >= scene.mNumMaterials) continue;
    aiString path;
    if (scene.mMaterials[index]->GetTexture(aiTextureType_DIFFUSE, 0, &path) == AI_SUCCESS && path.length > 0) {
      // Trimmed: exporters leave trailing blanks after map_Kd's file name.
      std::string name = path.C_Str();
      const size_t first = name.find_first_not_of(" \t\r\n"), last = name.find_last_not_of(" \t\r\n");
      return first == std::string::npos ? "" : name.substr(first, last - first + 1);
    }
  }
  return "";
}

TriangleMesh FromScene(const aiScene* scene, const Assimp::Importer& importer, const std::string& name,
                       std::string* texture) {
  if (!scene) Fail(name, std::string("not a readable OBJ or STL file (") + importer.GetErrorString() + ")");
  TriangleMesh mesh;
  bool all_normals = true, all_uvs = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& part = *scene->mMeshes[m];
    if (!(part.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    all_normals = all_normals && part.mNormals;
    all_uvs = all_uvs && part.mTextureCoords[0];
    Append(part, name, mesh);
  }
  if (mesh.triangles.empty()) Fail(name, "no triangles");
  // Normals and UVs are kept only where every part has them (a mesh half textured renders wrong).
  if (all_normals || all_uvs) {
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) AppendAttributes(*scene->mMeshes[m], mesh);
    if (!all_normals) mesh.normals.clear();
    if (!all_uvs) mesh.uvs.clear();
  }
  if (texture) *texture = DiffuseTexture(*scene);
  return mesh;
}

}  // namespace

TriangleMesh ReadMesh(const std::filesystem::path& file, std::string* texture) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) Fail(file.string(), "file not found");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), kPostProcess);
  return FromScene(scene, importer, file.string(), texture);
}

TriangleMesh ReadMeshFromMemory(const std::string& bytes, const std::string& extension_hint, const std::string& name,
                                std::string* texture) {
  if (bytes.empty()) Fail(name, "empty file");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), kPostProcess, extension_hint.c_str());
  return FromScene(scene, importer, name, texture);
}

}  // namespace sortcell::assets
