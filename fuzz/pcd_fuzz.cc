// Fuzz target: a PCD file as `sortcell segment`/`classify` read it (perception::LoadCloud, organized or
// not) and as the segmentation benchmark reads a labelled capture (LoadMosdObjectIds).
#include "fuzz/fuzz_input.h"
#include "perception/pcd_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "input.pcd";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::perception::LoadCloud(file, /*organized=*/false); });
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::perception::LoadCloud(file, /*organized=*/true); });
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::perception::LoadMosdObjectIds(file); });
  return 0;
}
