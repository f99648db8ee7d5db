// Ctrl-C while rlrun waits for SUMO: TrafficNetwork-v0 drives each SUMO from a worker process
// (rlrun-sumo-worker); rlrun's wait for its answer polls for Ctrl-C (core/worker_wait.hpp), so a
// worker that stops answering cannot keep rlrun from stopping. The real binary, real SUMO.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "envs/child_processes.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun::testing;

namespace {

// The CPU time (clock ticks) `pid` uses in the next second.
long cpu_ticks_over_a_second(pid_t pid) {
  const auto ticks = [pid] {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text;
    std::getline(in, text);
    std::stringstream rest(text.substr(text.rfind(')') + 2));
    std::string field;
    long utime = 0, stime = 0;
    for (int i = 3; i <= 15 && rest >> field; ++i) {  // fields 14 and 15: utime, stime
      if (i == 14) utime = std::stol(field);
      if (i == 15) stime = std::stol(field);
    }
    return utime + stime;
  };
  const long before = ticks();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  return ticks() - before;
}

}  // namespace

TEST_CASE("One Ctrl-C stops training while its SUMO worker does not answer", "[traffic]") {
  TempDir dir("sumo_worker_hang");
  const std::string config = dir / "network.yaml";
  std::ofstream(config) << "run: {name: hang, seed: 1, total_timesteps: 1000000, out_dir: "
                        << dir.str() << "/runs}\n"
                        << "env: {id: TrafficNetwork-v0, kwargs: {scenario: " << RLRUN_SOURCE_DIR
                        << "/scenarios/grid4x4.yaml}}\n"
                        << "algo: {id: PPO, n_steps: 64, batch_size: 256}\n";
  const std::string log = dir / "log.txt";
  const pid_t rlrun = start_rlrun({"train", config}, log);
  std::vector<pid_t> workers;
  REQUIRE(wait_until(
      [&] {
        workers = children_named(rlrun, "rlrun-sumo-work");
        return !workers.empty() && read_text(log).find("total_timesteps") != std::string::npos;
      },
      60));
  for (pid_t worker : workers) kill(worker, SIGSTOP);  // it will never answer
  // rlrun soon waits for it (its CPU time stands still), not in training's update.
  REQUIRE(wait_until([&] { return cpu_ticks_over_a_second(rlrun) <= 2; }, 60));
  kill(-rlrun, SIGINT);
  const int status = wait_exit(rlrun, 60);
  const std::string output = read_text(log);
  INFO(output);
  REQUIRE(status != -1);  // before: rlrun waited in recv() for ever, whatever the signals
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(output.find("the SUMO worker (pid ") != std::string::npos);
  // Stopped while it starts SUMO (the log line above can come before the start-up ends) or
  // while it runs a step: either way one Ctrl-C ends rlrun and says which wait it was.
  CHECK(
      (output.find("has not answered in a simulation step 5 s after Ctrl-C") != std::string::npos ||
       output.find("has not answered to start SUMO 5 s after Ctrl-C") != std::string::npos ||
       output.find("while waiting for the SUMO worker (pid ") != std::string::npos));
  CHECK(all_gone(workers, 10));  // killed, stopped or not
}
