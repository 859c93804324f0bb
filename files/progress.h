#pragma once
/// @file
/// Progress of long work on stderr: one updating line (count, rate, ETA) on a terminal, a line every
/// 10 % or 30 s otherwise (logs, CI).

#include <chrono>
#include <string>

namespace sortcell::files {

class Progress {
 public:
  Progress(std::string label, int total);
  /// Counts `n` more units done.
  void Advance(int n = 1);
  /// Ends the line (terminal) or prints the final count.
  void Finish();

 private:
  void Print(bool final);
  std::string label_;
  int total_ = 0, done_ = 0, last_decile_ = 0;
  bool terminal_ = false;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace sortcell::files
