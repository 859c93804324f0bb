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
///       field("yaw", v.yaw, files::kAdded);  // Records from before it lack it.
///     }
///   };
///   PoseFields RecordFieldsOf(const Pose*);
///   nlohmann::json j; files::WriteFields(j, pose);     files::ReadFields(j, "pose", pose);

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "files/json_fields.h"

namespace sortcell::files {

/// What a field is besides its key and member, as flags combined with |: how it is read, how records
/// pool into a group's figures (a sweep's), and whether it is a figure of the machine that ran it.
using FieldFlags = unsigned;
inline constexpr FieldFlags kRequired = 0;     ///< Every record has it: missing is an error (the default).
inline constexpr FieldFlags kAdded = 1u << 0;  ///< Later versions added it: records from before lack it, and
                                               ///< the member keeps its value.
inline constexpr FieldFlags kSum = 1u << 1;    ///< Pooled by summing (a map: key by key).
inline constexpr FieldFlags kMax = 1u << 2;    ///< Pooled as the largest.
/// A mean (a map of them), pooled weighted by the weight each record is given (a sweep: its grasp attempts).
inline constexpr FieldFlags kWeightedMean = 1u << 3;
/// Computed from the record's other fields: a pool computes it again from the pooled ones.
inline constexpr FieldFlags kDerived = 1u << 4;
/// The machine's (wall clock, memory): left out where two runs of the same work are compared.
inline constexpr FieldFlags kMachine = 1u << 5;
/// An optional key: written only when the member holds a value, read when present (never null).
inline constexpr FieldFlags kIfSet = 1u << 6;
/// One record's own: a pool of records (a sweep's group) leaves it out.
inline constexpr FieldFlags kUnpooled = 1u << 7;
/// The flags of the figures a pool has.
inline constexpr FieldFlags kPooled = kSum | kMax | kWeightedMean | kDerived;

// A member as JSON: optional ones as value or null.
template <typename T>
nlohmann::json FieldJson(const T& value) {
  return nlohmann::json(value);
}
template <typename T>
nlohmann::json FieldJson(const std::optional<T>& value) {
  return OrNull(value);
}

// Whether a member is written: an optional key only with a value.
template <typename T>
bool Written(const T&, FieldFlags) {
  return true;
}
template <typename T>
bool Written(const std::optional<T>& value, FieldFlags flags) {
  return value.has_value() || !(flags & kIfSet);
}

// Reads a member by its flags: optional ones accept null (or are absent, kIfSet).
template <typename T>
void ReadByRule(const nlohmann::json& j, const std::string& path, const char* key, T& out, FieldFlags flags) {
  if (flags & kAdded) {
    ReadAddedField(j, path, key, out);
  } else {
    ReadField(j, path, key, out);
  }
}
template <typename T>
void ReadByRule(const nlohmann::json& j, const std::string& path, const char* key, std::optional<T>& out,
                FieldFlags flags) {
  if (flags & kIfSet) {
    out.reset();
    if (!j.is_object() || !j.contains(key)) return;
    T value;
    ReadField(j, path, key, value);
    out = std::move(value);
  } else if (flags & kAdded) {
    ReadAddedNullable(j, path, key, out);
  } else {
    ReadNullable(j, path, key, out);
  }
}

/// The field list of `Record`: a type with `template <typename Self, typename F> static void Visit(Self& v,
/// F&&)`, calling `field(key, v.member)` or `field(key, v.member, flags)` for each key in turn, named by
/// `RecordFieldsOf(const Record*)` in the record's namespace.
template <typename Record>
using RecordFields = decltype(RecordFieldsOf(static_cast<const Record*>(nullptr)));

/// Writes the fields of `v` whose flags `keep(flags)` accepts into the object `j` (keys already in `j` are
/// kept unless written again). `Fields` is RecordFields<Record>, or another list of some of its fields (a
/// group written only in some records, or a member struct's fields written flat beside the record's own).
template <typename Record, typename Keep, typename Fields = RecordFields<Record>>
void WriteFieldsIf(nlohmann::json& j, const Record& v, Keep&& keep, Fields = {}) {
  if (!j.is_object()) j = nlohmann::json::object();
  Fields::Visit(v, [&](const char* key, const auto& member, FieldFlags flags = kRequired) {
    if (keep(flags) && Written(member, flags)) j[key] = FieldJson(member);
  });
}

/// Writes every field of `v` into the object `j`.
template <typename Record, typename Fields = RecordFields<Record>>
void WriteFields(nlohmann::json& j, const Record& v, Fields fields = {}) {
  WriteFieldsIf(
      j, v, [](FieldFlags) { return true; }, fields);
}

/// Writes the fields of `v` that have any of `any_of` (e.g. kPooled: a pool's figures).
template <typename Record, typename Fields = RecordFields<Record>>
void WriteFieldsWith(nlohmann::json& j, const Record& v, FieldFlags any_of, Fields fields = {}) {
  WriteFieldsIf(
      j, v, [any_of](FieldFlags flags) { return (flags & any_of) != 0; }, fields);
}

/// Writes the fields of `v` that have none of `none_of` (e.g. kUnpooled: what a pool of records has).
template <typename Record, typename Fields = RecordFields<Record>>
void WriteFieldsWithout(nlohmann::json& j, const Record& v, FieldFlags none_of, Fields fields = {}) {
  WriteFieldsIf(
      j, v, [none_of](FieldFlags flags) { return (flags & none_of) == 0; }, fields);
}

/// Reads every field of `v` from `j`; `path` is `j`'s place in the whole record for messages ("" at the top).
/// @throws std::invalid_argument naming the key (json_fields.h's messages).
template <typename Record, typename Fields = RecordFields<Record>>
void ReadFields(const nlohmann::json& j, const std::string& path, Record& v, Fields = {}) {
  Fields::Visit(
      v, [&](const char* key, auto& member, FieldFlags flags = kRequired) { ReadByRule(j, path, key, member, flags); });
}

/// The keys of `Record`'s fields that have any of `any_of`, in the list's order.
template <typename Record, typename Fields = RecordFields<Record>>
std::vector<std::string> FieldKeys(FieldFlags any_of, Fields = {}) {
  std::vector<std::string> keys;
  const Record probe{};
  Fields::Visit(probe, [&](const char* key, const auto&, FieldFlags flags = kRequired) {
    if (flags & any_of) keys.emplace_back(key);
  });
  return keys;
}

/// Calls `f(key, member_of_a, member_of_b, flags)` for each field of two records of one type, in step
/// (the list visited twice, in the same order: b's members are collected first, then a's are met).
template <typename Record, typename F, typename Fields = RecordFields<Record>>
void VisitInStep(Record& a, const Record& b, F&& f, Fields = {}) {
  std::vector<const void*> b_members;
  Fields::Visit(b, [&](const char*, const auto& member, FieldFlags = kRequired) { b_members.push_back(&member); });
  size_t i = 0;
  Fields::Visit(a, [&](const char* key, auto& member, FieldFlags flags = kRequired) {
    using Member = std::decay_t<decltype(member)>;
    f(key, member, *static_cast<const Member*>(b_members[i++]), flags);
  });
}

// One figure pooled: summed, the largest, or a weighted sum (made a mean by FinishPool).
template <typename T>
void PoolFigure(T& pooled, const T& one, FieldFlags flags, double weight) {
  if constexpr (std::is_arithmetic_v<T>) {
    if (flags & kSum) pooled += one;
    if (flags & kMax) pooled = std::max(pooled, one);
    if (flags & kWeightedMean) pooled += static_cast<T>(one * weight);
  } else if constexpr (std::is_same_v<T, std::map<std::string, double>>) {
    for (const auto& [key, value] : one) PoolFigure(pooled[key], value, flags, weight);
  }
}

/// Adds `one` into `pooled` as each field's flags say (kSum, kMax, kWeightedMean with `weight`); fields
/// without them are left as they are.
template <typename Record, typename Fields = RecordFields<Record>>
void PoolFields(Record& pooled, const Record& one, double weight, Fields fields = {}) {
  VisitInStep(
      pooled, one,
      [&](const char*, auto& into, const auto& from, FieldFlags flags) { PoolFigure(into, from, flags, weight); },
      fields);
}

/// Ends a pool whose weights came to `total_weight`: its weighted sums become means (left as they are
/// when the total is 0).
template <typename Record, typename Fields = RecordFields<Record>>
void FinishPool(Record& pooled, double total_weight, Fields = {}) {
  if (total_weight <= 0) return;
  Fields::Visit(pooled, [&](const char*, auto& member, FieldFlags flags = kRequired) {
    using Member = std::decay_t<decltype(member)>;
    if (!(flags & kWeightedMean)) return;
    if constexpr (std::is_arithmetic_v<Member>) {
      member /= total_weight;
    } else if constexpr (std::is_same_v<Member, std::map<std::string, double>>) {
      for (auto& [key, value] : member) value /= total_weight;
    }
  });
}

}  // namespace sortcell::files
