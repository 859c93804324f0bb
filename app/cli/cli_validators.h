#pragma once
/// @file
/// CLI11 validators and option parsing shared by the subcommands.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace sortcell::app {

/// Digits only: CLI11 itself would wrap "-3" into a huge uint64 seed.
inline const CLI::Validator kUnsignedInteger(
    [](std::string& value) -> std::string {
      if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos) {
        return "expected a non-negative integer, found '" + value + "'";
      }
      return "";
    },
    "UINT", "non-negative integer");

/// "WxH" for the review video: positive and even (H.264's 4:2:0 chroma halves both).
inline const CLI::Validator kVideoSize(
    [](std::string& value) -> std::string {
      int w = 0, h = 0;
      char x = 0, extra = 0;
      if (std::sscanf(value.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w <= 0 || h <= 0 ||
          w % 2 != 0 || h % 2 != 0 || value.find_first_not_of("0123456789x") != std::string::npos) {
        return "expected WIDTHxHEIGHT with even positive numbers, e.g. 1280x720, found '" + value + "'";
      }
      return "";
    },
    "WxH", "video size");

/// The width and height of a "WxH" that kVideoSize accepted.
inline std::pair<int, int> ParseVideoSize(const std::string& value) {
  int w = 0, h = 0;
  std::sscanf(value.c_str(), "%dx%d", &w, &h);
  return {w, h};
}

/// `parse(value)` for an option whose spelling names an enum value (e.g. ParseGrouping). Call it when
/// the command runs, not in a CLI11 callback, so that an unknown spelling is a one-line error.
/// @throws std::invalid_argument "<option>: <parse's message>" for an unknown spelling.
template <typename Parse>
auto ParseOption(const char* option, const std::string& value, Parse parse) {
  try {
    return parse(value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(option) + ": " + e.what());
  }
}

}  // namespace sortcell::app
