#include "sim/ffmpeg_pipe.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spdlog/fmt/fmt.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace sortcell::sim {
namespace {

std::runtime_error Failure(const std::filesystem::path& path, const std::string& what) {
  return std::runtime_error("video '" + path.string() + "': " + what);
}

// A temporary file for the child's stderr (so that its messages do not interleave with ours), open.
int TemporaryFile(std::filesystem::path& made) {
  std::string pattern = (std::filesystem::temp_directory_path() / "sortcell_ffmpeg_XXXXXX").string();
  const int fd = mkstemp(pattern.data());
  if (fd >= 0) made = pattern;
  return fd;
}

std::string LastLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

FfmpegPipe::FfmpegPipe(const std::filesystem::path& path, int width, int height, double fps)
    : path_(path), frame_bytes_(static_cast<size_t>(width) * height * 3) {
  // Created here first, so that a folder that does not exist is named now, not when ffmpeg exits.
  if (!std::ofstream(path, std::ios::binary)) throw Failure(path, "cannot be created");
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw Failure(path, std::string("no pipe: ") + std::strerror(errno));
  const std::string size = fmt::format("{}x{}", width, height), rate = fmt::format("{}", fps);
  // libx264 in yuv420p (what browsers and players take), the index at the front (plays while loading).
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-loglevel", "error", "-y", "-f", "rawvideo",
                                   "-pix_fmt", "bgr24", "-s", size, "-r", rate, "-i", "pipe:0",
                                   "-c:v", "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
                                   path.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int messages = TemporaryFile(messages_);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (messages >= 0) posix_spawn_file_actions_adddup2(&actions, messages, STDERR_FILENO);
  const int spawned = posix_spawnp(&child_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (messages >= 0) close(messages);
  if (spawned != 0) {
    close(fds[1]);
    child_ = -1;
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    if (!messages_.empty()) std::filesystem::remove(messages_, ignored);
    throw Failure(path, std::string("cannot start ffmpeg (install Debian's ffmpeg): ") + std::strerror(spawned));
  }
  fd_ = fds[1];
}

void FfmpegPipe::Write(const unsigned char* bgr) {
  // A write to a pipe whose reader has gone raises SIGPIPE in the writing thread: blocked here, it
  // stays pending and the write fails with EPIPE instead of ending the process.
  sigset_t pipe_signal, previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  size_t done = 0;
  while (fd_ >= 0 && done < frame_bytes_) {
    const ssize_t n = write(fd_, bgr + done, frame_bytes_ - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  if (done < frame_bytes_) {
    // Take the pending SIGPIPE (if any) before unblocking it.
    const timespec no_wait{0, 0};
    sigtimedwait(&pipe_signal, nullptr, &no_wait);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (done < frame_bytes_) throw Failure(path_, "ffmpeg stopped taking frames");
}

void FfmpegPipe::Close() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  if (child_ < 0) return;
  int status = 0;
  pid_t waited = -1;
  do {
    waited = waitpid(child_, &status, 0);
  } while (waited < 0 && errno == EINTR);
  const int wait_error = errno;
  child_ = -1;
  const std::string message = messages_.empty() ? "" : LastLine(messages_);
  std::error_code ignored;
  if (!messages_.empty()) std::filesystem::remove(messages_, ignored);
  messages_.clear();
  if (waited < 0) throw Failure(path_, std::string("ffmpeg's end not seen: ") + std::strerror(wait_error));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? fmt::format("ffmpeg failed (exit {})", WEXITSTATUS(status))
                                              : std::string("ffmpeg was killed");
    throw Failure(path_, message.empty() ? how : how + ": " + message);
  }
}

void CutVideo(const std::filesystem::path& in, const std::filesystem::path& out, double start_s, double length_s) {
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-loglevel", "error", "-y", "-ss", fmt::format("{:.3f}", start_s),
                                   "-i", in.string(), "-t", fmt::format("{:.3f}", length_s), "-an", "-c:v", "libx264",
                                   "-pix_fmt", "yuv420p", "-movflags", "+faststart", out.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::filesystem::path messages_file;
  const int messages = TemporaryFile(messages_file);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (messages >= 0) posix_spawn_file_actions_adddup2(&actions, messages, STDERR_FILENO);
  pid_t child = -1;
  const int spawned = posix_spawnp(&child, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (messages >= 0) close(messages);
  int status = 0;
  pid_t waited = -1;
  if (spawned == 0) {
    do {
      waited = waitpid(child, &status, 0);
    } while (waited < 0 && errno == EINTR);
  }
  const std::string message = messages_file.empty() ? "" : LastLine(messages_file);
  std::error_code ignored;
  if (!messages_file.empty()) std::filesystem::remove(messages_file, ignored);
  if (spawned != 0) throw Failure(out, std::string("cannot start ffmpeg (install Debian's ffmpeg): ") + std::strerror(spawned));
  if (waited < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw Failure(out, "ffmpeg could not cut '" + in.string() + "'" + (message.empty() ? "" : ": " + message));
  }
}

FfmpegPipe::~FfmpegPipe() {
  try {
    Close();
  } catch (...) {  // A destructor must not throw; Close() called first reports it.
  }
}

}  // namespace sortcell::sim
