// Fuzz target: a cell layout YAML (app::ReadCellFile: bins, rules, the reach and overlap checks), placed
// where the shipped layouts live.
#include "files/cell_file.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "scenes/cells/input.yaml";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::files::ReadCellFile(file); });
  return 0;
}
