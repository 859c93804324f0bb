#pragma once
/// @file
/// A record's JSON keys declared once: a record type lists its fields in one `RecordFields<T>::Visit`
/// (key, member, and whether the key came later), and writing and strict reading both follow from it,
/// as MuJoCo's mjxmacro.h lists each field once. Optional members travel as value-or-null.
///
///   template <> struct RecordFields<Pose> {
///     template <typename Self, typename F> static void Visit(Self& v, F&& field) {
///       field("x", v.x);
///       field("yaw", v.yaw, FieldRule::kAdded);  // Records from before it lack it.
///     }
///   };
///   nlohmann::json j; WriteFields(j, pose);     ReadFields(j, "pose", pose);

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/common/json_fields.h"

namespace sortcell::app {

/// How a key is read.
enum class FieldRule {
  kRequired,  ///< Every record has it: missing is an error.
  kAdded,     ///< Later versions added it: records from before lack it, and the member keeps its value.
};

// A member as JSON: optional ones as value or null.
template <typename T>
nlohmann::json FieldJson(const T& value) {
  return nlohmann::json(value);
}
template <typename T>
nlohmann::json FieldJson(const std::optional<T>& value) {
  return OrNull(value);
}

// Reads a member by its rule: optional ones accept null.
template <typename T>
void ReadByRule(const nlohmann::json& j, const std::string& path, const char* key, T& out, FieldRule rule) {
  if (rule == FieldRule::kAdded) {
    ReadAddedField(j, path, key, out);
  } else {
    ReadField(j, path, key, out);
  }
}
template <typename T>
void ReadByRule(const nlohmann::json& j, const std::string& path, const char* key, std::optional<T>& out,
                FieldRule rule) {
  if (rule == FieldRule::kAdded) {
    ReadAddedNullable(j, path, key, out);
  } else {
    ReadNullable(j, path, key, out);
  }
}

/// Specialised per record type with `template <typename Self, typename F> static void Visit(Self& v, F&&)`,
/// calling `field(key, v.member)` or `field(key, v.member, FieldRule::kAdded)` for each key in turn.
template <typename Record>
struct RecordFields;

/// Writes every field of `v` into the object `j` (keys already in `j` are kept unless declared again).
/// `Fields` is RecordFields<Record>, or another list of some of its fields (a group written only in some
/// records, or a member struct's fields written flat beside the record's own).
template <typename Record, typename Fields = RecordFields<Record>>
void WriteFields(nlohmann::json& j, const Record& v, Fields = {}) {
  if (!j.is_object()) j = nlohmann::json::object();
  Fields::Visit(
      v, [&](const char* key, const auto& member, FieldRule = FieldRule::kRequired) { j[key] = FieldJson(member); });
}

/// Reads every field of `v` from `j`; `path` is `j`'s place in the whole record for messages ("" at the top).
/// @throws std::invalid_argument naming the key (json_fields.h's messages).
template <typename Record, typename Fields = RecordFields<Record>>
void ReadFields(const nlohmann::json& j, const std::string& path, Record& v, Fields = {}) {
  Fields::Visit(v, [&](const char* key, auto& member, FieldRule rule = FieldRule::kRequired) {
    ReadByRule(j, path, key, member, rule);
  });
}

}  // namespace sortcell::app
