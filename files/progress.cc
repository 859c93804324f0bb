#include "files/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace sortcell::files {
namespace {

double Seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

Progress::Progress(std::string label, int total)
    : label_(std::move(label)),
      total_(total),
      terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

void Progress::Advance(int n) {
  done_ += n;
  const auto now = std::chrono::steady_clock::now();
  const int decile = total_ > 0 ? 10 * done_ / total_ : 0;
  if (terminal_ ? Seconds(now - last_print_) > 0.2 : (decile > last_decile_ || Seconds(now - last_print_) > 30)) {
    last_decile_ = decile;
    last_print_ = now;
    Print(false);
  }
}

void Progress::Finish() { Print(true); }

void Progress::Print(bool final) {
  const double elapsed = Seconds(std::chrono::steady_clock::now() - start_);
  const double rate = elapsed > 0 ? done_ / elapsed : 0;
  const double eta = rate > 0 ? (total_ - done_) / rate : 0;
  std::fprintf(stderr, "%s%s: %d/%d (%.1f/s, %s %.0f s)%s", terminal_ ? "\r" : "", label_.c_str(), done_, total_, rate,
               final ? "took" : "ETA", final ? elapsed : eta, terminal_ && !final ? "   " : "\n");
  std::fflush(stderr);
}

}  // namespace sortcell::files
