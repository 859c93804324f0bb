#pragma once
/// @file
/// CLI11 validators and option parsing shared by the subcommands.

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>

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
