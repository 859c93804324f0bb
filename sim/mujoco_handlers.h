#pragma once
/// @file
/// MuJoCo's process-wide error and warning hooks. The 2.2 defaults print and then wait on getchar(),
/// which hangs a headless run; these never touch the terminal's input.

#include <stdexcept>
#include <string>

namespace sortcell::sim {

/// Thrown when MuJoCo reports a fatal error (mju_error) inside the engine.
class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Installs the handlers once per process (idempotent, thread-safe): errors throw MujocoError,
/// warnings are counted and logged once each. Every sim entry point calls this.
void InstallMujocoHandlers();

/// Text of the most recent MuJoCo warning in this process ("" if none), and how many there were.
std::string LastMujocoWarning();
int MujocoWarningCount();

}  // namespace sortcell::sim
