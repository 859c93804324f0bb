// Fuzz target: a user's mesh file (assets::ReadMesh, assimp underneath), read as OBJ and as STL.
#include "assets/mesh_reader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path& root = sortcell_fuzz::ScratchDir();
  for (const char* name : {"input.obj", "input.stl"}) {
    const std::filesystem::path file = root / name;
    sortcell_fuzz::WriteInput(file, data, size);
    sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::assets::ReadMesh(file); });
  }
  return 0;
}
