#pragma once
/// @file
/// CLI11 validators shared by the subcommands.

#include <CLI/CLI.hpp>

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

}  // namespace sortcell::app
