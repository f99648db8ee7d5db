// No Python worker outlives rlrun: Ctrl-C (SIGINT to the whole foreground process group, as a
// terminal sends it) stops the run cleanly and the workers with it; `kill -9` of rlrun takes
// the workers down too (PR_SET_PDEATHSIG). The real binary, the real interpreter.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "envs/python_env_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

namespace {

// "R", "S", "Z", ... of /proc/<pid>/stat, or "" when the process is gone.
std::string process_state(pid_t pid, pid_t* parent = nullptr, std::string* name = nullptr) {
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

bool alive(pid_t pid) {
  const std::string state = process_state(pid);
  return !state.empty() && state != "Z" && state != "X";
}

std::vector<pid_t> python_children(pid_t parent) {
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    pid_t ppid = 0;
    std::string comm;
    const pid_t pid = std::stoi(name);
    if (alive(pid) && !process_state(pid, &ppid, &comm).empty() && ppid == parent &&
        comm.rfind("python", 0) == 0)
      found.push_back(pid);
  }
  return found;
}

// Starts `rlrun train` on 4 Python envs, in a process group of its own (as a shell's job),
// and waits until its 4 workers run. Returns rlrun's pid and the workers'.
pid_t start_training(const std::string& dir, std::vector<pid_t>& workers,
                     const std::string& env_id = "python:rlrun_test_envs.cartpole:CartPolePort",
                     const char* started = "total_timesteps") {
  const std::string config = python_experiment(dir, "long", env_id, "id: PPO, n_steps: 64",
                                               10000000, 4, ", max_episode_steps: 500");
  const std::string log = dir + "/log.txt";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    setenv("PYTHONPATH", (kSourceDir + "/tests/python_envs").c_str(), 1);
    execl(RLRUN_BINARY, RLRUN_BINARY, "train", config.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < until) {
    workers = python_children(pid);
    if (workers.size() >= 4 && read_text(log).find(started) != std::string::npos)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return pid;
}

// Waits up to `seconds` for the child to exit; its wait status, or -1.
int wait_exit(pid_t pid, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < until) {
    if (waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

bool all_gone(const std::vector<pid_t>& pids, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    bool any = false;
    for (pid_t p : pids) any = any || alive(p);
    if (!any) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

}  // namespace

TEST_CASE("Ctrl-C stops a run on Python envs and leaves no worker behind", "[python]") {
  TempDir dir("python_sigint");
  std::vector<pid_t> workers;
  const pid_t rlrun = start_training(dir.str(), workers);
  REQUIRE(workers.size() == 4);
  kill(-rlrun, SIGINT);  // the whole group, as the terminal does
  const int status = wait_exit(rlrun, 60);
  INFO(read_text(dir / "log.txt"));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);  // interrupted: checkpoint saved, resume printed
  CHECK(read_text(dir / "log.txt").find("Traceback") == std::string::npos);
  CHECK(all_gone(workers, 5));
}

TEST_CASE("kill -9 of rlrun takes its Python workers down", "[python]") {
  TempDir dir("python_sigkill");
  std::vector<pid_t> workers;
  const pid_t rlrun = start_training(dir.str(), workers);
  REQUIRE(workers.size() == 4);
  kill(rlrun, SIGKILL);
  int status = 0;
  waitpid(rlrun, &status, 0);
  CHECK(all_gone(workers, 5));
}

TEST_CASE("A second Ctrl-C stops rlrun while a Python env hangs in step()", "[python]") {
  TempDir dir("python_hang");
  std::vector<pid_t> workers;
  const pid_t rlrun =
      start_training(dir.str(), workers, "python:rlrun_test_envs.broken:HangsInStep", "training PPO");
  REQUIRE(workers.size() == 4);
  std::this_thread::sleep_for(std::chrono::seconds(2));  // every worker is stuck at step 5
  kill(-rlrun, SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(-rlrun, SIGINT);
  const int status = wait_exit(rlrun, 30);
  INFO(read_text(dir / "log.txt"));
  REQUIRE(status != -1);  // it stopped (wait_exit kills it after 30 s and returns -1)
  CHECK(read_text(dir / "log.txt").find("second Ctrl-C") != std::string::npos);
  CHECK(all_gone(workers, 10));
}
