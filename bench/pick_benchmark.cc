// Wall-clock time and real-time factor of `sortcell pick` (scripted pick-and-place, physics at
// 500 Hz, control at 500 Hz), for every paper object without video, and with the 1280x720 30 fps
// review video for one object. Prints a Markdown table.
#include <cstdio>
#include <filesystem>
#include <string>

#include "simcell/scripted_pick.h"
#include "bench_temp_dir.h"

int main() {
  namespace fs = std::filesystem;
  const fs::path root = SORTCELL_SOURCE_DIR;
  const fs::path out = BenchTempDir("sortcell_pick_benchmark");
  struct Case {
    const char* object;
    const char* bin;
    bool video;
  };
  const Case cases[] = {{"bottle1", "bottle", false}, {"cup", "cup", false},        {"ball", "ball", false},
                        {"bottle2", "others", false}, {"bottle3", "others", false}, {"box", "others", false},
                        {"ball", "ball", true}};
  std::printf("| object | bin | video | status | slip (mm) | cycle (sim s) | wall (s) | real-time factor |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    sortcell::simcell::PickOptions options;
    options.scene = root / "scenes/cell.xml";
    options.object = c.object;
    options.bin = c.bin;
    options.out = out / c.object;
    if (c.video) options.video = out / "pick.mp4";
    const sortcell::simcell::PickResult r = sortcell::simcell::RunPick(options, {"pick_benchmark"});
    std::printf("| %s | %s | %s | %s | %.2f | %.2f | %.2f | %.1f |\n", c.object, c.bin, c.video ? "yes" : "no",
                r.status.c_str(), r.slip_mm, r.cycle_time_s, r.wall_time_s, r.real_time_factor);
  }
  return 0;
}
