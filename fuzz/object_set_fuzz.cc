// Fuzz target: an object-set YAML (app::LoadObjectSet), placed where the shipped sets live so that its
// model paths resolve as theirs do.
#include "files/object_set.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path& root = sortcell_fuzz::ScratchDir();
  sortcell_fuzz::LinkFromSource(root, "models");
  const std::filesystem::path file = root / "scenes/objects/input.yaml";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::files::LoadObjectSet(file); });
  return 0;
}
