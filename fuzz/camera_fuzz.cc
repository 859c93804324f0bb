// Fuzz target: a camera.json (app::LoadCameraPose), as `sortcell segment --camera` reads it.
#include "files/camera_file.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "camera.json";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::files::LoadCameraPose(file); });
  return 0;
}
