#include "parallel_runs.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/private_temp_dir.hpp"

namespace rlrun::cli {

namespace {

struct Child {
  size_t index = 0;
  std::string log_path;
};

// The last `n` lines of a file.
std::string tail_lines(const std::string& path, size_t n) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string out;
  for (size_t i = lines.size() > n ? lines.size() - n : 0; i < lines.size(); ++i)
    out += "    " + lines[i] + "\n";
  return out;
}

// The trainer's summary line ("trained N steps in ... model saved to ...").
std::string summary_line(const std::string& path) {
  std::ifstream in(path);
  std::string found;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("trained ", 0) == 0 || line.rfind("interrupted after ", 0) == 0 ||
        line.rfind("sweep: ", 0) == 0)
      found = line;
  return found;
}

// `log_fd`: the child's console log, opened close-on-exec by the caller.
pid_t start_child(const std::vector<std::string>& child_args, int log_fd) {
  std::vector<std::string> args{"/proc/self/exe"};
  args.insert(args.end(), child_args.begin(), child_args.end());
  // argv is built before fork(): this process may have a ForkJoin worker thread, and the child
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
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kExecFailed, sizeof(kExecFailed) - 1);
    _exit(127);
  }
  return pid;
}

}  // namespace

int train_in_parallel(const std::vector<std::string>& configs,
                      const std::vector<std::string>& child_options, int jobs) {
  std::vector<ChildRun> runs;
  for (const std::string& config : configs) {
    ChildRun run{config, {"--threads", "1", "train", config}};
    run.args.insert(run.args.end(), child_options.begin(), child_options.end());
    runs.push_back(run);
  }
  return run_in_parallel(runs, jobs, "experiments");
}

int run_in_parallel(const std::vector<ChildRun>& configs, int jobs, const std::string& what) {
  // A private directory (mkdtemp, 0700; core/private_temp_dir.hpp): a name in /tmp others can
  // predict could hold their symlinks.
  PrivateTempDir log_dir("rlrun-train-");
  install_interrupt_handlers();
  std::cout << "training " << configs.size() << " " << what << ", " << jobs
            << " at a time (console output of each in " << log_dir.path() << "/)" << std::endl;

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
      const std::string log_name = std::to_string(next) + ".log";
      Child child{next, log_dir.file(log_name)};
      const int log_fd = log_dir.create_file(log_name);
      pid_t pid = -1;
      try {
        pid = start_child(configs[next].args, log_fd);
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
    std::cout << "[" << finished << "/" << configs.size() << "] " << configs[child.index].label << ": ";
    if (code == 0) {
      std::cout << summary_line(child.log_path) << std::endl;
    } else if (code == 130) {
      std::cout << "interrupted\n" << tail_lines(child.log_path, 2) << std::flush;
    } else {
      ++failures;
      std::cout << "FAILED (exit " << code << "), end of its output (" << child.log_path
                << "):\n"
                << tail_lines(child.log_path, 8) << std::flush;
    }
  }
  if (next < configs.size())
    std::cout << configs.size() - next << " " << what << " were not started" << std::endl;
  if (failures > 0) {
    log_dir.keep();  // the logs of the failed runs, named above
    return 1;
  }
  return interrupted ? 130 : 0;  // the logs go: each run's output is also in its log.txt
}

}  // namespace rlrun::cli
