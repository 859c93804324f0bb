// Fuzz target: a dataset folder (app::LoadDataset): manifest.json, then a line "--descriptors.csv--",
// then descriptors.csv.
#include "training/dataset.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path dir = sortcell_fuzz::ScratchDir() / "dataset";
  const auto [manifest, descriptors] = sortcell_fuzz::SplitAt(data, size, "\n--descriptors.csv--\n");
  sortcell_fuzz::WriteInput(dir / "manifest.json", reinterpret_cast<const uint8_t*>(manifest.data()), manifest.size());
  sortcell_fuzz::WriteInput(dir / "descriptors.csv", reinterpret_cast<const uint8_t*>(descriptors.data()),
                            descriptors.size());
  sortcell_fuzz::ExpectReadOrRefusal(dir, [&] { sortcell::training::LoadDataset(dir); });
  return 0;
}
