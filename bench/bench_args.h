#pragma once
// A benchmark's command line and errors, as the CLI treats them: parsed by CLI11; a bad flag, value or
// file is one line naming it and exit code 2, never an abort; --help prints the usage.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

// A whole number >= `at_least` (CLI11's Range says "not in range" of a word, and prints the double
// limit of an unbounded one in full).
inline CLI::Validator WholeNumberAtLeast(int at_least) {
  return CLI::Validator(
      [at_least](const std::string& text) -> std::string {
        int value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error == std::errc() && end == text.data() + text.size() && value >= at_least) return "";
        return "expected a whole number >= " + std::to_string(at_least) + ", got '" + text + "'";
      },
      "INT>=" + std::to_string(at_least));
}

// Parses `argv` into the options of `app`. Returns the exit code when the benchmark should stop at once
// (--help: 0), none when it should run; a bad command line throws std::invalid_argument with CLI11's
// message on one line.
inline std::optional<int> ParseBenchmarkArgs(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw std::invalid_argument(message + " (see --help)");
  }
  return std::nullopt;
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
