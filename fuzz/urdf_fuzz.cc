// Fuzz target: a user's object URDF, imported whole (assets::ImportObject: the URDF, the meshes it
// names, their texture, the checks and the files written), beside a small textured cube and a
// two-piece collision STL it may name (meshes/cube.obj, meshes/pieces.stl).
#include "assets/object_import.h"
#include "fuzz/fuzz_input.h"

namespace {

void WriteMeshes(const std::filesystem::path& root) {
  std::filesystem::create_directories(root / "meshes");
  std::ofstream(root / "meshes/cube.obj") << "mtllib cube.mtl\nv 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\n"
                                             "vt 0 0\nvt 1 0\nvt 0 1\nusemtl skin\nf 1/1 3/3 2/2\nf 1/1 2/2 4/3\n"
                                             "f 1/1 4/3 3/3\nf 2/2 3/3 4/3\n";
  std::ofstream(root / "meshes/cube.mtl") << "newmtl skin\nmap_Kd skin.png\n";
  // A 1x1 PNG.
  static const unsigned char kPng[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
      0x0c, 0x49, 0x44, 0x41, 0x54, 0x08, 0xd7, 0x63, 0xf8, 0xcf, 0xc0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0x18,
      0xdd, 0x8d, 0xb0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  std::ofstream(root / "meshes/skin.png", std::ios::binary).write(reinterpret_cast<const char*>(kPng), sizeof kPng);
  std::ofstream(root / "meshes/pieces.stl")
      << "solid p\n"
         "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0.04 0\nvertex 0.04 0 0\nendloop\nendfacet\n"
         "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0.04 0 0\nvertex 0 0 0.04\nendloop\nendfacet\n"
         "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0.04\nvertex 0 0.04 0\nendloop\nendfacet\n"
         "facet normal 0 0 0\nouter loop\nvertex 0.04 0 0\nvertex 0 0.04 0\nvertex 0 0 0.04\nendloop\nendfacet\n"
         "endsolid p\n";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path root = [] {
    WriteMeshes(sortcell_fuzz::ScratchDir());
    return sortcell_fuzz::ScratchDir();
  }();
  const std::filesystem::path file = root / "input.urdf";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell::assets::ObjectSource source;
  source.name = "input";
  source.urdf = file;
  std::error_code ec;
  std::filesystem::remove_all(root / "cache", ec);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::assets::ImportObject(source, root / "cache"); });
  return 0;
}
