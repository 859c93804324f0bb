#pragma once
/// @file
/// One spelling table per enum, used both to print a value and to parse it back (CLI values, YAML keys,
/// the JSON records): each enum's names are written once, beside the enum's other facts. Hand-written
/// because the library that does this by reflection (magic_enum) is not packaged in Debian bookworm.
///
///   constexpr EnumNames<Colour, 2> kColourNames{{{Colour::kRed, "red"}, {Colour::kBlue, "blue"}}};
///   NameOf(kColourNames, Colour::kRed)             -> "red"
///   ParseName(kColourNames, "blue", "colour")      -> Colour::kBlue
///   ParseName(kColourNames, "pink", "colour")      -> throws "unknown colour 'pink' (expected red or blue)"

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sortcell {

template <typename E, std::size_t N>
using EnumNames = std::array<std::pair<E, const char*>, N>;

/// The spelling of `value`; "?" for a value outside the table (a cast integer).
template <typename E, std::size_t N>
constexpr const char* NameOf(const EnumNames<E, N>& names, E value) {
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return "?";
}

/// The value spelled `text`, or nothing.
template <typename E, std::size_t N>
constexpr std::optional<E> FindName(const EnumNames<E, N>& names, std::string_view text) {
  for (const auto& [v, name] : names) {
    if (text == name) return v;
  }
  return std::nullopt;
}

/// The spellings in the table's order, for a CLI's list of choices.
template <typename E, std::size_t N>
std::vector<std::string> AllNames(const EnumNames<E, N>& names) {
  std::vector<std::string> all;
  all.reserve(N);
  for (const auto& entry : names) all.emplace_back(entry.second);
  return all;
}

/// "a, b or c": the spellings for an error message.
template <typename E, std::size_t N>
std::string ExpectedNames(const EnumNames<E, N>& names) {
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) {
    expected += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i].second);
  }
  return expected;
}

/// The value spelled `text`.
/// @throws std::invalid_argument "unknown <what> '<text>' (expected a, b or c)".
template <typename E, std::size_t N>
E ParseName(const EnumNames<E, N>& names, std::string_view text, std::string_view what) {
  if (const std::optional<E> value = FindName(names, text)) return *value;
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(text) + "' (expected " +
                              ExpectedNames(names) + ")");
}

}  // namespace sortcell
