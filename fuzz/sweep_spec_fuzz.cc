// Fuzz target: a sweep spec (app::LoadSweepSpec), placed where the shipped specs live so that its
// scene, object-set and model paths resolve as theirs do; also with a --set override taken from the
// input's first line.
#include "app/sweep/sweep_spec.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path& root = sortcell_fuzz::ScratchDir();
  for (const char* name :
       {"models", "scenes/cell.xml", "scenes/produce.xml", "scenes/flange_tool.inc.xml", "scenes/objects"}) {
    sortcell_fuzz::LinkFromSource(root, name);
  }
  const std::filesystem::path file = root / "scenes/sweeps/input.yaml";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] {
    const sortcell::app::SweepSpec spec = sortcell::app::LoadSweepSpec(file);
    for (int e = 0; e < std::min(spec.EpisodeCount(), 50); ++e) spec.Episode(e);
  });
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string first_line = text.substr(0, text.find('\n'));
  sortcell_fuzz::ExpectReadOrRefusal(
      file, [&] { sortcell::app::LoadSweepSpec(file, {first_line}); }, "--set");
  return 0;
}
