#pragma once
/// @file
/// A record's JSON keys declared once: a record type lists its fields in one `Visit` (key, member, and
/// whether the key came later), and writing and strict reading both follow from it, as MuJoCo's
/// mjxmacro.h lists each field once. Optional members travel as value-or-null. The list is named, in
/// the record's own namespace, by a declaration `RecordFieldsOf` that argument-dependent lookup finds
/// (declared only, never defined), so that records in any library can list their fields:
///
///   struct PoseFields {
///     template <typename Self, typename F> static void Visit(Self& v, F&& field) {
///       field("x", v.x);
///       field("yaw", v.yaw, files::FieldRule::kAdded);  // Records from before it lack it.
///     }
///   };
///   PoseFields RecordFieldsOf(const Pose*);
///   nlohmann::json j; files::WriteFields(j, pose);     files::ReadFields(j, "pose", pose);

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "files/json_fields.h"

namespace sortcell::files {

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

/// The field list of `Record`: a type with `template <typename Self, typename F> static void Visit(Self& v,
/// F&&)`, calling `field(key, v.member)` or `field(key, v.member, FieldRule::kAdded)` for each key in
/// turn, named by `RecordFieldsOf(const Record*)` in the record's namespace.
template <typename Record>
using RecordFields = decltype(RecordFieldsOf(static_cast<const Record*>(nullptr)));

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

}  // namespace sortcell::files
