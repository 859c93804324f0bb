// Fuzz target: a sweep's results.jsonl as --resume reads it (app::ReadSweepResults): good lines read,
// damaged ones listed.
#include "app/sweep/sweep_record.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = sortcell_fuzz::ScratchDir() / "results.jsonl";
  sortcell_fuzz::WriteInput(file, data, size);
  sortcell_fuzz::ExpectReadOrRefusal(file, [&] { sortcell::app::ReadSweepResults(file); });
  return 0;
}
