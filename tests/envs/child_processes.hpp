#pragma once
// Watching the real rlrun binary and the worker processes it starts (Python env workers,
// rlrun-sumo-worker), for the tests of Ctrl-C, kill -9 and hangs: rlrun is started as a shell
// starts a job (a process group of its own), its children are found in /proc.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_paths.hpp"

namespace rlrun::testing {

// "R", "S", "Z", ... of /proc/<pid>/stat, or "" when the process is gone.
inline std::string process_state(pid_t pid, pid_t* parent = nullptr, std::string* name = nullptr) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(in, text)) return "";
  const auto open = text.find('('), close = text.rfind(')');
  if (name) *name = text.substr(open + 1, close - open - 1);
  std::stringstream rest(text.substr(close + 2));
  std::string state;
  long ppid = 0;
  rest >> state >> ppid;
  if (parent) *parent = static_cast<pid_t>(ppid);
  return state;
}

inline bool alive(pid_t pid) {
  const std::string state = process_state(pid);
  return !state.empty() && state != "Z" && state != "X";
}

// The live children of `parent` whose command name starts with `prefix` ("python", "rlrun-sumo").
inline std::vector<pid_t> children_named(pid_t parent, const std::string& prefix) {
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    pid_t ppid = 0;
    std::string comm;
    const pid_t pid = std::stoi(name);
    if (alive(pid) && !process_state(pid, &ppid, &comm).empty() && ppid == parent &&
        comm.rfind(prefix, 0) == 0)
      found.push_back(pid);
  }
  return found;
}

inline std::vector<pid_t> python_children(pid_t parent) { return children_named(parent, "python"); }

// Starts `rlrun ARGS` in a process group of its own (as a shell's job), its output to `log`,
// the test envs importable. `ignore_sigint`: as a non-interactive shell starts `rlrun ... &`.
inline pid_t start_rlrun(const std::vector<std::string>& args, const std::string& log,
                         bool ignore_sigint = false) {
  std::vector<std::string> argv_text{RLRUN_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string python_path = std::string(RLRUN_SOURCE_DIR) + "/tests/python_envs";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    setenv("PYTHONPATH", python_path.c_str(), 1);
    setenv("SUMO_HOME", "/usr/share/sumo", 0);
    signal(SIGINT, ignore_sigint ? SIG_IGN : SIG_DFL);
    execv(argv[0], argv.data());
    _exit(127);
  }
  setpgid(pid, pid);
  return pid;
}

// Waits up to `seconds` until `ready()` holds; whether it did.
template <class Ready>
bool wait_until(Ready ready, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return ready();
}

// Waits up to `seconds` for the child to exit; its wait status, or -1 (then it is killed).
inline int wait_exit(pid_t pid, double seconds) {
  int status = 0;
  if (wait_until([&] { return waitpid(pid, &status, WNOHANG) == pid; }, seconds)) return status;
  kill(-pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

inline bool all_gone(const std::vector<pid_t>& pids, double seconds) {
  return wait_until(
      [&] {
        for (pid_t p : pids)
          if (alive(p)) return false;
        return true;
      },
      seconds);
}

}  // namespace rlrun::testing
