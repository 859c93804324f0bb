#include "files/output_dir.h"

#include <mujoco/mujoco.h>
#include <pcl/pcl_config.h>
#include <Eigen/Core>
#include <opencv2/core/version.hpp>
#include <spdlog/fmt/chrono.h>
#include <spdlog/fmt/fmt.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include "sortcell/git_revision.h"

namespace sortcell::files {

std::string SystemReason(int error) { return error != 0 ? std::string(": ") + std::strerror(error) : std::string(); }

namespace {

constexpr std::string_view kPartialMark = ".partial";

// The process that writes `file` beside its final name (WriteTextFile: "<name>.partial<pid>"), or 0
// when `file` is not such a file.
pid_t PartialFileWriter(const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  const size_t mark = name.rfind(kPartialMark);
  if (mark == std::string::npos || mark == 0) return 0;
  const std::string digits = name.substr(mark + kPartialMark.size());
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return static_cast<pid_t>(std::stol(digits));
}

}  // namespace

void RemoveStalePartialFiles(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const pid_t writer = PartialFileWriter(entry.path());
    // A live writer may be about to rename it; a dead one (killed mid-write) never will.
    if (writer <= 0 || !entry.is_regular_file(ec) || ::kill(writer, 0) == 0 || errno != ESRCH) continue;
    fs::remove(entry.path(), ec);
  }
}

void PrepareOutputDir(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw std::invalid_argument("output folder '" + dir.string() + "': exists and is not a folder");
  }
  fs::create_directories(dir, ec);
  if (ec) throw std::invalid_argument("output folder '" + dir.string() + "': cannot create it: " + ec.message());
  const fs::path probe = dir / ".sortcell_write_test";
  {
    std::ofstream out(probe);
    if (!out.good()) throw std::invalid_argument("output folder '" + dir.string() + "': not writable");
  }
  fs::remove(probe, ec);
}

void CloseChecked(std::ofstream& out, const std::filesystem::path& path) {
  if (out.is_open()) out.close();  // Flushes: a full disk shows here, not at the last <<.
  if (!out) {
    throw std::runtime_error("cannot write '" + path.string() + "'" + SystemReason(errno));
  }
}

namespace {

void WriteInPlace(const std::filesystem::path& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  CloseChecked(out, path);
}

// Before the rename: otherwise a lost machine (power, kernel) may keep the rename but not the text,
// leaving an empty file where the old one was (a sweep's spec.yaml, read again by --resume).
void SyncFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  const bool synced = fd >= 0 && ::fsync(fd) == 0;
  const int reason = errno;
  if (fd >= 0) ::close(fd);
  errno = reason;
  if (!synced) throw std::runtime_error("cannot sync '" + path.string() + "'");
}

// So that the rename itself outlives a lost machine. Best effort: not every file system syncs folders.
void SyncFolder(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void WriteTextFile(const std::filesystem::path& path, const std::string& text) {
  std::error_code ec;
  const auto status = std::filesystem::symlink_status(path, ec);
  // A device, pipe or link is written in place (through the link): replacing it would lose what it is.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return WriteInPlace(path, text);
  // Written beside it and renamed over it: a process killed mid-write (a sweep's SIGKILL) leaves the
  // old file or the new one, never half of one.
  const std::filesystem::path partial = path.string() + std::string(kPartialMark) + std::to_string(::getpid());
  try {
    WriteInPlace(partial, text);
    SyncFile(partial);
  } catch (const std::runtime_error&) {
    const int reason = errno;
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw std::runtime_error("cannot write '" + path.string() + "'" + SystemReason(reason));
  }
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw std::runtime_error("cannot write '" + path.string() + "': " + ec.message());
  }
  SyncFolder(path.parent_path());
}

std::string ReadTextFile(const std::filesystem::path& path) {
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  // read(), not `out << in.rdbuf()`: that one turns a read error (a folder, an I/O error) into a short text.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) text.append(chunk, static_cast<size_t>(in.gcount()));
  if (!in.is_open() || in.bad()) {
    throw std::runtime_error("cannot read '" + path.string() + "'" + SystemReason(errno));
  }
  return text;
}

void WriteJson(const std::filesystem::path& path, const nlohmann::json& json) {
  WriteTextFile(path, json.dump(2) + '\n');
}

std::string CsvField(const std::string& value) {
  if (value.find_first_of(",\"\r\n") == std::string::npos) return value;
  std::string quoted = "\"";
  for (char c : value) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

nlohmann::json RunRecord(const std::vector<std::string>& command_line, uint64_t seed, const nlohmann::json& extra) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  const std::string started = fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(now));
  nlohmann::json run = {
      {"command_line", command_line},
      {"seed", seed},
      {"git_revision", SORTCELL_GIT_REVISION},
      {"versions",
       {{"mujoco", mj_versionString()},
        {"pcl", PCL_VERSION_PRETTY},
        {"opencv", CV_VERSION},
        {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                      std::to_string(EIGEN_MINOR_VERSION)}}},
      {"started_utc", started},
  };
  for (const auto& [key, value] : extra.items()) run[key] = value;
  return run;
}

}  // namespace sortcell::files
