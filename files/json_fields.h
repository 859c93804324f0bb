#pragma once
/// @file
/// Strict reading of JSON records into structs: a missing key or a value of the wrong type is an
/// error that names the key (with its path, e.g. "summary.grasp_attempts"), never a silent default.

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace sortcell::files {

/// What a JSON value must be to read as a T, for messages; and whether it is (integers in range, no
/// fractions for integers).
template <typename T>
const char* JsonExpectedType() {
  if constexpr (std::is_same_v<T, std::string>)
    return "a string";
  else if constexpr (std::is_same_v<T, bool>)
    return "true or false";
  else if constexpr (std::is_unsigned_v<T>)
    return "a non-negative integer";
  else if constexpr (std::is_integral_v<T>)
    return "an integer";
  else if constexpr (std::is_floating_point_v<T>)
    return "a number";
  else
    return "a value";
}

template <typename T>
bool JsonHolds(const nlohmann::json& value) {
  if constexpr (std::is_same_v<T, std::string>) {
    return value.is_string();
  } else if constexpr (std::is_same_v<T, bool>) {
    return value.is_boolean();
  } else if constexpr (std::is_integral_v<T>) {
    if (value.is_number_unsigned()) {
      return value.get<uint64_t>() <= static_cast<uint64_t>(std::numeric_limits<T>::max());
    }
    if (!value.is_number_integer()) return false;
    const int64_t v = value.get<int64_t>();
    return std::is_signed_v<T> && v >= static_cast<int64_t>(std::numeric_limits<T>::min()) &&
           v <= static_cast<int64_t>(std::numeric_limits<T>::max());
  } else if constexpr (std::is_floating_point_v<T>) {
    return value.is_number();
  } else {
    return true;
  }
}

/// A found value for messages: scalars as written, lists and objects by kind.
inline std::string JsonFound(const nlohmann::json& value) {
  if (value.is_array()) return "a list";
  if (value.is_object()) return "an object";
  const std::string text = value.dump();
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

/// Reads `json[key]` into `out`. `path` is the path of `json` in the record ("" at the top).
/// @throws std::invalid_argument "<path.key>: missing" or "<path.key>: expected <type>, found <type>"
///         (or the enum's own message naming the value).
template <typename T>
void ReadField(const nlohmann::json& json, const std::string& path, const char* key, T& out) {
  const std::string name = path.empty() ? key : path + "." + key;
  if (!json.is_object())
    throw std::invalid_argument((path.empty() ? std::string("record") : path) + ": expected an object");
  const auto it = json.find(key);
  if (it == json.end()) throw std::invalid_argument(name + ": missing");
  if constexpr (std::is_same_v<T, bool>) {
    if (!it->is_boolean()) throw std::invalid_argument(name + ": expected true or false, found " + it->type_name());
  } else if constexpr (std::is_arithmetic_v<T>) {
    if (!it->is_number()) throw std::invalid_argument(name + ": expected a number, found " + it->type_name());
    if (!JsonHolds<T>(*it))
      throw std::invalid_argument(name + ": expected " + JsonExpectedType<T>() + ", found " + JsonFound(*it));
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!it->is_string()) throw std::invalid_argument(name + ": expected a string, found " + it->type_name());
  }
  try {
    out = it->template get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(name + ": expected another type, found " + std::string(it->type_name()) + " (" +
                                e.what() + ")");
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(name + ": " + e.what());
  }
}

/// As ReadField, for a key that must be present but may be null.
template <typename T>
void ReadNullable(const nlohmann::json& json, const std::string& path, const char* key, std::optional<T>& out) {
  const std::string name = path.empty() ? key : path + "." + key;
  if (!json.is_object() || !json.contains(key)) throw std::invalid_argument(name + ": missing");
  if (json[key].is_null()) {
    out.reset();
    return;
  }
  T value;
  ReadField(json, path, key, value);
  out = value;
}

/// As ReadField, for a key that later versions added: absent leaves `out` as it is.
template <typename T>
void ReadAddedField(const nlohmann::json& json, const std::string& path, const char* key, T& out) {
  if (json.is_object() && json.contains(key)) ReadField(json, path, key, out);
}

/// As ReadNullable, for a key that later versions added: absent leaves `out` as it is.
template <typename T>
void ReadAddedNullable(const nlohmann::json& json, const std::string& path, const char* key, std::optional<T>& out) {
  if (json.is_object() && json.contains(key)) ReadNullable(json, path, key, out);
}

/// A value or JSON null.
template <typename T>
nlohmann::json OrNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace sortcell::files
