#pragma once
// Runs the real rlrun binary (or another command) and captures exit code and output, for
// end-to-end tests of the CLI as a user types it.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "test_paths.hpp"

namespace rlrun::testing {

// A whole text file ("" when it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CommandResult {
  int exit_code = -1;
  std::string output;     // stdout and stderr together
  long peak_rss_kb = -1;  // run_command_measured only: the child's peak resident memory
};

inline CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
    result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// Like run_command, and the peak resident set size (VmHWM) of the command, from wait4's
// rusage (`exec` makes the command itself the child the shell would otherwise wait for).
inline CommandResult run_command_measured(const std::string& command) {
  CommandResult result;
  int fds[2];
  if (pipe(fds) != 0) return result;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    close(fds[0]);
    close(fds[1]);
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::array<char, 4096> buffer;
  ssize_t n = 0;
  while ((n = read(fds[0], buffer.data(), buffer.size())) > 0)
    result.output.append(buffer.data(), n);
  close(fds[0]);
  int status = 0;
  struct rusage usage {};
  if (wait4(pid, &status, 0, &usage) == pid) {
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.peak_rss_kb = usage.ru_maxrss;
  }
  return result;
}

inline CommandResult run_rlrun(const std::string& args) {
  return run_command(std::string(RLRUN_BINARY) + " " + args);
}

// A fresh temporary directory, removed when the object goes away. The process id is part of
// the name: test binaries of other build directories may run the same test at the same time.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("rlrun_test_" + name + "_" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string str() const { return path_.string(); }
  std::string operator/(const std::string& child) const { return (path_ / child).string(); }

 private:
  std::filesystem::path path_;
};

// "Billion laughs" YAML text (about 1 KB): a0 lists ten values, each of a1..a9 ten references
// to the level below, so the document expands to 10^10 values. Built by appending only (GCC 12
// warns -Wrestrict, falsely, about `"literal" + std::to_string(...)` chains).
inline std::string yaml_alias_bomb() {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 9; ++i) {
    const std::string level = std::to_string(i), below = std::to_string(i - 1);
    text += 'a';
    text += level;
    text += ": &a";
    text += level;
    text += " [";
    for (int k = 0; k < 10; ++k) {
      text += "*a";
      text += below;
      text += k < 9 ? ", " : "]\n";
    }
  }
  return text;
}

}  // namespace rlrun::testing
