#pragma once
// A benchmark's command line and errors, as the CLI treats them: a bad value or file is one line naming
// it and exit code 2, never an abort.
#include <charconv>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

// `text` as a whole number >= `at_least`; throws naming `what` (the flag or argument) otherwise.
inline int CountArg(const std::string& what, const std::string& text, int at_least) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < at_least) {
    throw std::invalid_argument(what + ": expected a whole number >= " + std::to_string(at_least) + ", got '" + text + "'");
  }
  return value;
}

// Runs `body` (returning the exit code); an exception becomes "TOOL: what" on stderr and exit code 2.
template <class Body>
int RunBenchmark(const char* tool, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 2;
  }
}
