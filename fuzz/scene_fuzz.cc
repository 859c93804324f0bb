// Fuzz target: an object model (an MJCF fragment, as models/objects/*.inc.xml) composed into the cell
// and compiled (sim::LoadComposedCell), as an object set's models are.
#include "fuzz/fuzz_input.h"
#include "sim/scene_composer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "input.inc.xml";
  sortcell_fuzz::WriteInput(file, data, size);
  const std::filesystem::path models = std::filesystem::path(SORTCELL_SOURCE_DIR) / "models";
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::sim::LoadComposedCell(models, {file}, file.string()); });
  return 0;
}
