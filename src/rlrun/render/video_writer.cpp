#include "rlrun/render/video_writer.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/find_executable.hpp"
#include "rlrun/core/process_settings.hpp"
#include "rlrun/core/temp_beside.hpp"
#include "rlrun/render/video_limits.hpp"
#include "rlrun/render/yuv420.hpp"

extern char** environ;

namespace rlrun {

namespace {

constexpr size_t kErrorTailBytes = 1500;

std::string errno_text() { return std::strerror(errno); }

bool is_executable_file(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// A pipe whose reader has gone must fail write() with EPIPE instead of killing rlrun.
void ignore_sigpipe() {
  struct sigaction current;
  if (::sigaction(SIGPIPE, nullptr, &current) == 0 && current.sa_handler == SIG_DFL)
    std::signal(SIGPIPE, SIG_IGN);
}

std::string fps_text(double fps) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", fps);
  return buffer;
}

// ffmpeg reads an output name with a "proto:" prefix as a protocol (file:, pipe:, tcp:, ...),
// so a user's `--output file:x.mp4` or `pipe:1` would not name a file. Its file protocol with an
// absolute path names exactly one file, whatever the characters in it.
std::string ffmpeg_file_url(const std::string& path) {
  return "file:" + std::filesystem::absolute(path).string();
}

// ffmpeg's command line: raw yuv420p frames on stdin, H.264 in an mp4 at output_url. The
// stream is tagged BT.601 limited range, which is what render/yuv420.hpp's conversion produces.
std::vector<std::string> ffmpeg_arguments(const std::string& ffmpeg, int width, int height,
                                          const VideoOptions& options,
                                          const std::string& output_url) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  std::vector<std::string> args = {ffmpeg,
                                   "-hide_banner",
                                   "-nostdin",
                                   "-loglevel",
                                   "error",
                                   "-f",
                                   "rawvideo",
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-video_size",
                                   size,
                                   "-framerate",
                                   fps_text(options.fps),
                                   "-i",
                                   "pipe:0",
                                   "-an",
                                   "-c:v",
                                   "libx264",
                                   "-preset",
                                   options.preset,
                                   "-crf",
                                   std::to_string(options.crf),
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-colorspace",
                                   "smpte170m",
                                   "-color_primaries",
                                   "smpte170m",
                                   "-color_trc",
                                   "smpte170m",
                                   "-color_range",
                                   "tv",
                                   "-movflags",
                                   "+faststart",
                                   "-f",
                                   "mp4",
                                   "-y",
                                   output_url};
  return args;
}

// posix_spawn of args[0] with stdin, stdout (when >= 0) and stderr redirected, in its own
// process group (a terminal's Ctrl-C stays with rlrun). Returns posix_spawn's error number.
int spawn_in_own_group(std::vector<std::string> args, int stdin_fd, int stdout_fd, int stderr_fd,
                       pid_t* pid) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, stdin_fd, 0);
  if (stdout_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stdout_fd, 1);
  posix_spawn_file_actions_adddup2(&actions, stderr_fd, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  const int rc = ::posix_spawn(pid, args[0].c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return rc;
}

}  // namespace

std::string VideoWriter::find_ffmpeg() {
  if (const std::string& chosen = process_settings().ffmpeg; !chosen.empty()) {
    if (!is_executable_file(chosen))
      throw RuntimeFailure("RLRUN_FFMPEG=" + chosen + " is not an executable file");
    return chosen;
  }
  if (const std::string found = find_executable("ffmpeg"); !found.empty()) return found;
  throw RuntimeFailure(
      "cannot record video: the `ffmpeg` program is not on PATH. Install the Debian package "
      "`ffmpeg` (sudo apt-get install ffmpeg; scripts/setup.sh does it) or set RLRUN_FFMPEG to "
      "an ffmpeg executable. (`rlrun record --frames DIR` writes PNG frames without ffmpeg.)");
}

VideoWriter::VideoWriter(std::string path, int width, int height, const VideoOptions& options)
    : path_(std::move(path)), width_(width), height_(height) {
  if (const std::string problem = check_video_size(width, height); !problem.empty())
    throw std::invalid_argument(problem);
  if (!(options.fps > 0 && options.fps <= kMaxVideoFps))
    throw std::invalid_argument("video fps must be > 0 and <= " +
                                std::to_string(static_cast<int>(kMaxVideoFps)));
  const std::string ffmpeg = find_ffmpeg();
  ignore_sigpipe();

  const std::filesystem::path parent = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw RuntimeFailure("cannot create directory " + parent.string() + ": " + ec.message());
  yuv_.resize(static_cast<size_t>(width) * height * 3 / 2);

  std::string stderr_template =
      (std::filesystem::temp_directory_path() / "rlrun-ffmpeg-stderr-XXXXXX").string();
  stderr_fd_ = ::mkostemp(stderr_template.data(), O_CLOEXEC);
  if (stderr_fd_ < 0) throw RuntimeFailure("cannot create a temporary file: " + errno_text());
  ::unlink(stderr_template.c_str());  // readable through the fd, gone from the disk
  try {
    const TempBeside temp = create_temp_beside(path_, ".part");  // ffmpeg writes it (-y)
    ::close(temp.fd);
    temp_path_ = temp.path;
  } catch (...) {
    ::close(stderr_fd_);
    throw;
  }

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    const std::string reason = errno_text();
    abort();  // removes the temporary file
    throw RuntimeFailure("cannot create a pipe to ffmpeg: " + reason);
  }
  const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);

  // Frames arrive as yuv420p already (render/yuv420.hpp); ffmpeg only encodes.
  const int rc = spawn_in_own_group(
      ffmpeg_arguments(ffmpeg, width, height, options, ffmpeg_file_url(temp_path_)), fds[0],
      devnull, stderr_fd_, &pid_);
  ::close(fds[0]);
  if (devnull >= 0) ::close(devnull);
  if (rc != 0) {
    ::close(fds[1]);
    pid_ = -1;
    abort();  // removes the temporary file
    throw RuntimeFailure("cannot start " + ffmpeg + ": " + std::strerror(rc));
  }
  pipe_fd_ = fds[1];
}

VideoWriter::~VideoWriter() { abort(); }

void VideoWriter::write(const Frame& frame) {
  if (pipe_fd_ < 0) throw std::logic_error("VideoWriter::write after close() or a failure");
  if (frame.width() != width_ || frame.height() != height_)
    throw std::invalid_argument("frame is " + std::to_string(frame.width()) + "x" +
                                std::to_string(frame.height()) + " but the video is " +
                                std::to_string(width_) + "x" + std::to_string(height_));
  rgb24_to_yuv420p(frame.pixels(), frame.stride_pixels(), width_, height_, yuv_.data());
  const char* data = reinterpret_cast<const char*>(yuv_.data());
  size_t done = 0;
  while (done < yuv_.size()) {
    const ssize_t n = ::write(pipe_fd_, data + done, yuv_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("ffmpeg stopped reading frames (" + errno_text() + ")");
    done += static_cast<size_t>(n);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (pipe_fd_ < 0 && pid_ < 0) return;
  if (frames_ == 0) fail("no frames were recorded");
  ::close(pipe_fd_);
  pipe_fd_ = -1;
  const int status = wait_for_exit();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status)
                                ? "exit code " + std::to_string(WEXITSTATUS(status))
                                : "killed by signal " + std::to_string(WTERMSIG(status));
    fail("ffmpeg failed (" + how + ")");
  }
  std::error_code ec;
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) fail("cannot rename " + temp_path_ + " to " + path_ + ": " + ec.message());
  ::close(stderr_fd_);
  stderr_fd_ = -1;
}

void VideoWriter::abort() noexcept {
  if (pipe_fd_ >= 0) {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
  }
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    wait_for_exit();
  }
  if (!temp_path_.empty()) {
    std::error_code ec;
    std::filesystem::remove(temp_path_, ec);
  }
  if (stderr_fd_ >= 0) {
    ::close(stderr_fd_);
    stderr_fd_ = -1;
  }
}

void VideoWriter::fail(const std::string& what) {
  // Let ffmpeg finish writing its complaint before reading it.
  if (pipe_fd_ >= 0) {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
  }
  if (pid_ > 0) wait_for_exit();
  std::string message = "cannot write video " + path_ + ": " + what;
  const std::string tail = error_tail();
  if (!tail.empty()) message += "; ffmpeg said:\n" + tail;
  abort();
  throw RuntimeFailure(message);
}

int VideoWriter::wait_for_exit() noexcept {
  int status = 0;
  if (pid_ <= 0) return status;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return status;
}

std::string VideoWriter::error_tail() const {
  if (stderr_fd_ < 0) return "";
  const off_t size = ::lseek(stderr_fd_, 0, SEEK_END);
  if (size <= 0) return "";
  const off_t start = size > static_cast<off_t>(kErrorTailBytes) ? size - kErrorTailBytes : 0;
  std::string text(static_cast<size_t>(size - start), '\0');
  const ssize_t n = ::pread(stderr_fd_, text.data(), text.size(), start);
  text.resize(n > 0 ? static_cast<size_t>(n) : 0);
  if (start > 0) {
    const size_t newline = text.find('\n');
    if (newline != std::string::npos) text.erase(0, newline + 1);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace rlrun
