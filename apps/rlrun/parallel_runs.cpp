#include "parallel_runs.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/line_reader.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun::cli {

namespace {

struct Child {
  size_t index = 0;
  std::string log_path;
};

// A child's console log line by line (`sweep run` keeps them in the sweep's directory, which
// may come from anyone: not through a link, a regular file, within bounds; lines cut at 64 KiB).
std::optional<LineReader> read_log(const std::string& path) {
  FileDescriptor fd;
  try {
    fd = open_regular_file(AT_FDCWD, path, O_RDONLY, path);
  } catch (const RuntimeFailure&) {
    return std::nullopt;  // the child's output is a courtesy here; the exit code tells the rest
  }
  if (!fd) return std::nullopt;
  return LineReader(std::move(fd), path, uint64_t{1} << 30, size_t{64} << 10,
                    LineReader::LongLines::kCut);
}

// The last `n` lines of a file.
std::string tail_lines(const std::string& path, size_t n) {
  std::deque<std::string> lines;
  std::optional<LineReader> in = read_log(path);
  try {
    for (std::string line; in && in->next(line);) {
      lines.push_back(line);
      if (lines.size() > n) lines.pop_front();
    }
  } catch (const RuntimeFailure&) {
  }
  std::string out;
  for (const std::string& line : lines) out += "    " + line + "\n";
  return out;
}

// The trainer's summary line ("trained N steps in ... model saved to ...").
std::string summary_line(const std::string& path) {
  std::optional<LineReader> in = read_log(path);
  std::string found;
  try {
    for (std::string line; in && in->next(line);)
      if (line.rfind("trained ", 0) == 0 || line.rfind("interrupted after ", 0) == 0 ||
          line.rfind("sweep: ", 0) == 0 || line.rfind("this worker: ", 0) == 0)
        found = line;
  } catch (const RuntimeFailure&) {
  }
  return found;
}

// `log_fd`: the child's console log, opened close-on-exec by the caller.
pid_t start_child(const std::vector<std::string>& child_args, int log_fd) {
  std::vector<std::string> args{"/proc/self/exe"};
  args.insert(args.end(), child_args.begin(), child_args.end());
  // argv is built before fork(): this process may have thread-pool workers, and the child
  // of a threaded process may only call async-signal-safe functions (no malloc) until exec.
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw RuntimeFailure("cannot start a training process (fork failed)");
  if (pid == 0) {
    setpgid(0, 0);  // Ctrl-C at the terminal goes to the parent only; it forwards one SIGINT
    dup2(log_fd, STDOUT_FILENO);  // the copies are not close-on-exec; log_fd itself is
    dup2(log_fd, STDERR_FILENO);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    execv(argv[0], argv.data());
    const char kExecFailed[] = "rlrun: cannot start /proc/self/exe (exec failed)\n";
    [[maybe_unused]] const ssize_t written =
        write(STDERR_FILENO, kExecFailed, sizeof(kExecFailed) - 1);
    _exit(127);
  }
  return pid;
}

// A child's own console log (ChildRun::log_path), opened close-on-exec for appending: a resumed
// run's output follows its earlier sessions', after a line saying when and what started.
int open_child_log(const ChildRun& run) {
  const std::filesystem::path path(run.log_path);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  // Not through a link, and a regular file (a FIFO would block here; core/regular_file.hpp).
  int fd = -1;
  try {
    fd = open_regular_file(AT_FDCWD, run.log_path, O_WRONLY | O_CREAT | O_APPEND, run.log_path)
             .release();
  } catch (const RuntimeFailure& e) {
    throw RuntimeFailure(std::string(e.what()) + " (the console output of " + run.label + ")");
  }
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &local);
  std::string header = std::string("=== ") + when + ": rlrun";
  for (const std::string& arg : run.args) header += " " + arg;
  header += " ===\n";
  if (write(fd, header.data(), header.size()) != static_cast<ssize_t>(header.size())) {
    const std::string reason = std::strerror(errno);
    close(fd);
    throw RuntimeFailure("cannot write " + run.log_path + ": " + reason);
  }
  return fd;
}

}  // namespace

int threads_per_job(const ExecutionContext& execution, int jobs) {
  return std::max(1, execution.threads() / std::max(1, jobs));
}

int train_in_parallel(const std::vector<std::string>& configs,
                      const std::vector<std::string>& child_options, int jobs,
                      int threads_per_run) {
  std::vector<ChildRun> runs;
  for (const std::string& config : configs) {
    ChildRun run{config, {"--threads", std::to_string(threads_per_run), "train", config}, ""};
    run.args.insert(run.args.end(), child_options.begin(), child_options.end());
    runs.push_back(run);
  }
  return run_in_parallel(runs, jobs, "experiment");
}

int run_in_parallel(const std::vector<ChildRun>& configs, int jobs, const std::string& noun,
                    const std::string& logs) {
  // A private directory (mkdtemp, 0700; core/private_temp_dir.hpp) for the children without a
  // log of their own: a name in /tmp others can predict could hold their symlinks.
  std::optional<PrivateTempDir> log_dir;
  if (logs.empty() || std::any_of(configs.begin(), configs.end(),
                                  [](const ChildRun& run) { return run.log_path.empty(); }))
    log_dir.emplace("rlrun-train-");
  install_interrupt_handlers();
  const std::string where =
      !logs.empty() ? logs
                    : "console output of each in " + log_dir->path() +
                          "/ while it runs, kept if one fails; each run's log.txt keeps it too";
  std::cout << "training " << count_of(static_cast<int64_t>(configs.size()), noun) << ", " << jobs
            << " at a time (" << where << ")" << std::endl;

  std::map<pid_t, Child> running;
  size_t next = 0, finished = 0;
  int failures = 0, forwarded = 0;
  bool interrupted = false;
  while (finished < configs.size()) {
    // Forward each Ctrl-C received (the first also stops starting new runs).
    while (forwarded < interrupt_count()) {
      interrupted = true;
      for (const auto& [pid, child] : running) kill(pid, SIGINT);
      ++forwarded;
    }
    while (!interrupted && running.size() < static_cast<size_t>(jobs) && next < configs.size()) {
      const ChildRun& run = configs[next];
      const std::string log_name = std::to_string(next) + ".log";
      Child child{next, run.log_path.empty() ? log_dir->file(log_name) : run.log_path};
      const int log_fd =
          run.log_path.empty() ? log_dir->create_file(log_name) : open_child_log(run);
      pid_t pid = -1;
      try {
        pid = start_child(run.args, log_fd);
      } catch (...) {
        close(log_fd);
        throw;
      }
      close(log_fd);
      running[pid] = child;
      ++next;
    }
    if (running.empty()) break;  // interrupted before the rest started
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    const Child child = running.at(pid);
    running.erase(pid);
    ++finished;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::cout << "[" << finished << "/" << configs.size() << "] " << configs[child.index].label
              << ": ";
    if (code == 0) {
      std::cout << summary_line(child.log_path) << std::endl;
    } else if (code == 130) {
      // A temporary log goes at the end: name only one that stays.
      const bool kept = !configs[child.index].log_path.empty();
      std::cout << "interrupted" << (kept ? " (output in " + child.log_path + ")" : std::string())
                << "\n"
                << tail_lines(child.log_path, 2) << std::flush;
    } else {
      ++failures;
      std::cout << "FAILED (exit " << code << "), end of its output (" << child.log_path << "):\n"
                << tail_lines(child.log_path, 8) << std::flush;
    }
  }
  if (next < configs.size())
    std::cout << "not started: " << count_of(static_cast<int64_t>(configs.size() - next), noun)
              << std::endl;
  if (failures > 0) {
    if (log_dir) log_dir->keep();  // the logs of the failed runs, named above
    return 1;
  }
  return interrupted ? 130 : 0;  // temporary logs go: each run's output is also in its log.txt
}

std::string own_binary() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? "rlrun" : exe.string();
}

}  // namespace rlrun::cli
