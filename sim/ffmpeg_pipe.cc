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

// Starts ffmpeg with `args`, its stdin from `stdin_fd` (-1: none), its stdout to /dev/null and its
// stderr into a temporary file (`messages`, empty if none could be made). Returns posix_spawnp's error.
int StartFfmpeg(std::vector<std::string> args, int stdin_fd, pid_t& child, std::filesystem::path& messages) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int messages_fd = TemporaryFile(messages);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdin_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (messages_fd >= 0) posix_spawn_file_actions_adddup2(&actions, messages_fd, STDERR_FILENO);
  const int spawned = posix_spawnp(&child, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (messages_fd >= 0) close(messages_fd);
  if (spawned != 0) {
    child = -1;
    std::error_code ignored;
    if (!messages.empty()) std::filesystem::remove(messages, ignored);
    messages.clear();
  }
  return spawned;
}

// Waits for ffmpeg `child` and removes its messages file. @throws as Failure(path, ...), with ffmpeg's
// last message, when it failed.
void FinishFfmpeg(pid_t child, std::filesystem::path& messages, const std::filesystem::path& path) {
  int status = 0;
  pid_t waited = -1;
  do {
    waited = waitpid(child, &status, 0);
  } while (waited < 0 && errno == EINTR);
  const int wait_error = errno;
  const std::string message = messages.empty() ? "" : LastLine(messages);
  std::error_code ignored;
  if (!messages.empty()) std::filesystem::remove(messages, ignored);
  messages.clear();
  if (waited < 0) throw Failure(path, std::string("ffmpeg's end not seen: ") + std::strerror(wait_error));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? fmt::format("ffmpeg failed (exit {})", WEXITSTATUS(status))
                                              : std::string("ffmpeg was killed");
    throw Failure(path, message.empty() ? how : how + ": " + message);
  }
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
  std::vector<std::string> args = {"ffmpeg",   "-nostdin",  "-loglevel",  "error",      "-y",      "-f",
                                   "rawvideo", "-pix_fmt",  "bgr24",      "-s",         size,      "-r",
                                   rate,       "-i",        "pipe:0",     "-c:v",       "libx264", "-pix_fmt",
                                   "yuv420p",  "-movflags", "+faststart", path.string()};
  const int spawned = StartFfmpeg(args, fds[0], child_, messages_);
  close(fds[0]);
  if (spawned != 0) {
    close(fds[1]);
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
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
  const pid_t child = child_;
  child_ = -1;
  FinishFfmpeg(child, messages_, path_);
}

void CutVideo(const std::filesystem::path& in, const std::filesystem::path& out, double start_s, double length_s) {
  std::vector<std::string> args = {"ffmpeg",
                                   "-nostdin",
                                   "-loglevel",
                                   "error",
                                   "-y",
                                   "-ss",
                                   fmt::format("{:.3f}", start_s),
                                   "-i",
                                   in.string(),
                                   "-t",
                                   fmt::format("{:.3f}", length_s),
                                   "-an",
                                   "-c:v",
                                   "libx264",
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-movflags",
                                   "+faststart",
                                   out.string()};
  pid_t child = -1;
  std::filesystem::path messages;
  const int spawned = StartFfmpeg(args, -1, child, messages);
  if (spawned != 0)
    throw Failure(out, std::string("cannot start ffmpeg (install Debian's ffmpeg): ") + std::strerror(spawned));
  try {
    FinishFfmpeg(child, messages, out);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + " (cutting '" + in.string() + "')");
  }
}

FfmpegPipe::~FfmpegPipe() {
  try {
    Close();
  } catch (...) {  // A destructor must not throw; Close() called first reports it.
  }
}

}  // namespace sortcell::sim
