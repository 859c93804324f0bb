#include "sim/mujoco_handlers.h"

#include <mujoco/mujoco.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <mutex>

namespace sortcell::sim {
namespace {

std::mutex warning_mutex;
std::string last_warning;
std::atomic<int> warning_count{0};

void OnError(const char* message) {
  // Unwinding through MuJoCo's C frames is safe here: x86-64 objects carry unwind tables, and
  // mj_loadXML catches engine errors during compilation itself.
  throw MujocoError(std::string("MuJoCo error: ") + message);
}

void OnWarning(const char* message) {
  warning_count.fetch_add(1);
  std::lock_guard<std::mutex> lock(warning_mutex);
  last_warning = message;
  spdlog::warn("MuJoCo: {}", message);
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = OnError;
    mju_user_warning = OnWarning;
  });
}

std::string LastMujocoWarning() {
  std::lock_guard<std::mutex> lock(warning_mutex);
  return last_warning;
}

int MujocoWarningCount() { return warning_count.load(); }

}  // namespace sortcell::sim
