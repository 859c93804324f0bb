#include "app/sweep/sweep_record.h"

#include <array>
#include <cerrno>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "files/json_fields.h"
#include "files/output_dir.h"

namespace sortcell::app {
namespace {

// What a failed episode's record says of the failure.
struct FailureFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("exit_code", v.exit_code, files::kIfSet);
    field("signal", v.signal, files::kIfSet);
    field("error", v.error, files::kIfSet);
  }
};

struct ReplayRecipeFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    field("arguments", v.arguments);
    field("build", v.build);
    field("model_digest", v.model_digest);
  }
};

// Checks what the types alone do not: the index, the seed and the axes' kinds.
void CheckRecordValues(const nlohmann::json& j) {
  if (!j["episode"].is_number_integer() || j["episode"].get<int64_t>() < 0) {
    throw std::invalid_argument("episode: expected a non-negative integer, found " + j["episode"].dump());
  }
  if (!j["seed"].is_number_unsigned()) {
    throw std::invalid_argument("seed: expected a non-negative integer, found " + j["seed"].dump());
  }
  if (!j["axes"].is_object())
    throw std::invalid_argument(std::string("axes: expected an object, found ") + j["axes"].type_name());
}

// One line of results.jsonl. @throws std::invalid_argument naming the key.
SweepRecord ParseRecord(std::string_view line) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(line.begin(), line.end());
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for a number past a double.
    throw std::invalid_argument(std::string("not a JSON record (damaged line?): ") + e.what());
  }
  try {
    return j.get<SweepRecord>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("not a sweep record: ") + e.what());
  }
}

}  // namespace

const char* ToString(RunStatus status) { return NameOf(kRunStatusNames, status); }

RunStatus ParseRunStatus(std::string_view text) { return ParseName(kRunStatusNames, text, "run status"); }

nlohmann::json WithoutMachineFigures(nlohmann::json record) {
  for (const std::string& key : files::FieldKeys<SweepRecord>(files::kMachine)) record.erase(key);
  if (!record.contains("summary") || !record["summary"].is_object()) return record;
  nlohmann::json& summary = record["summary"];
  for (const std::string& key : files::FieldKeys<simcell::RunFigures>(files::kMachine)) summary.erase(key);
  if (summary.contains("physics_profile") && summary["physics_profile"].is_object()) {
    for (const char* key : {"collision_s", "constraint_s", "smooth_s", "step_s"}) summary["physics_profile"].erase(key);
  }
  return record;
}

void to_json(nlohmann::json& j, const ReplayRecipe& v) { files::WriteFields(j, v, ReplayRecipeFields{}); }

void from_json(const nlohmann::json& j, ReplayRecipe& v) {
  files::ReadFields(j, "", v, ReplayRecipeFields{});
  if (v.arguments.empty()) throw std::invalid_argument("arguments: expected the episode's arguments, found none");
}

void to_json(nlohmann::json& j, const SweepRecord& v) {
  files::WriteFields(j, v);
  if (v.ok()) {
    j["summary"] = v.summary;
    j["items"] = v.items;
  } else {
    files::WriteFields(j, v, FailureFields{});
  }
}

void from_json(const nlohmann::json& j, SweepRecord& v) {
  if (!j.is_object()) throw std::invalid_argument(std::string("record: expected an object, found ") + j.type_name());
  files::ReadFields(j, "", v);
  CheckRecordValues(j);
  v.summary = simcell::EpisodeSummary{};
  v.items.clear();
  if (v.ok()) ReadSummaryAndItems(j, v.summary, v.items);
  files::ReadFields(j, "", v, FailureFields{});
}

void ReadSummaryAndItems(const nlohmann::json& json, simcell::EpisodeSummary& summary,
                         std::vector<simcell::ItemResult>& items) {
  if (!json.is_object())
    throw std::invalid_argument(std::string("record: expected an object, found ") + json.type_name());
  const auto s = json.find("summary");
  if (s == json.end()) throw std::invalid_argument("summary: missing");
  from_json(*s, summary);  // Its messages name "summary.<key>".
  const auto list = json.find("items");
  if (list == json.end()) throw std::invalid_argument("items: missing");
  if (!list->is_array()) throw std::invalid_argument(std::string("items: expected a list, found ") + list->type_name());
  items.clear();
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string where = "items[" + std::to_string(i) + "]";
    const nlohmann::json& item = (*list)[i];
    if (!item.is_object()) throw std::invalid_argument(where + ": expected an object, found " + item.type_name());
    try {
      items.push_back(item.get<simcell::ItemResult>());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + "." + e.what());  // ItemResult's messages start with the key.
    }
  }
}

std::vector<SweepRecord> ReadSweepFolder(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / "results.jsonl";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::invalid_argument("'" + dir.string() + "': not a sweep folder (no results.jsonl)");
  }
  SweepResults results = ReadSweepResults(file);
  if (!results.damaged.empty()) {
    throw std::invalid_argument(results.damaged.front() + " (run `sortcell sweep --resume` on '" + dir.string() +
                                "' first)");
  }
  return std::move(results.records);
}

std::string AxesText(const nlohmann::json& axes) {
  std::string text;
  for (const auto& [name, value] : axes.items()) {
    text += (text.empty() ? "" : ", ") + name + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
  }
  return text;
}

SweepResults ReadSweepResults(const std::filesystem::path& file) {
  SweepResults results;
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return results;
  const std::string text = files::ReadTextFile(file);
  results.file_bytes = text.size();
  size_t start = 0;
  int line = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // No newline: cut short, no record.
    ++line;
    const std::string_view content(text.data() + start, end - start);
    start = end + 1;
    results.complete_bytes = start;
    if (content.find_first_not_of(" \t\r") != std::string_view::npos) {
      try {
        results.records.push_back(ParseRecord(content));
      } catch (const std::invalid_argument& e) {
        results.damaged.push_back(file.string() + " line " + std::to_string(line) + ": " + e.what());
        continue;
      }
    }
    results.good_text.append(content).push_back('\n');
  }
  return results;
}

SweepResultsWriter::SweepResultsWriter(std::filesystem::path file) : file_(std::move(file)) {
  errno = 0;
  out_.open(file_, std::ios::binary | std::ios::app);
  if (!out_) throw std::runtime_error("cannot append to '" + file_.string() + "'" + files::SystemReason(errno));
}

void SweepResultsWriter::Append(const SweepRecord& record) {
  // A worker's log line may hold bytes that are not UTF-8: replaced, not a reason to lose the record.
  const std::string line = nlohmann::json(record).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  errno = 0;
  out_ << line << '\n';
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write '" + file_.string() + "'" + files::SystemReason(errno));
}

void SweepResultsWriter::Close() { files::CloseChecked(out_, file_); }

}  // namespace sortcell::app
