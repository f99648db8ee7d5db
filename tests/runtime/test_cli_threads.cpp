// --threads N|auto / RLRUN_THREADS: the thread count changes the speed of a run, never its
// result — 1, 2, 3 and 8 threads on any machine (more threads than cores included) train the
// same tensors, bit for bit.
#include <sched.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "runtime/cli_runner.hpp"
#include "runtime/same_tensors.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

struct Case {
  const char* name;
  const char* algo;
  const char* env;
  int n_envs;
  const char* algo_settings;
};

std::string write_config(const TempDir& dir, const Case& c) {
  const std::string path = dir / (std::string(c.name) + ".yaml");
  std::ofstream(path) << "run: {name: " << c.name
                      << ", seed: 4, total_timesteps: 1500, out_dir: " << dir.str() << "/runs}\n"
                      << "env: {id: " << c.env << ", n_envs: " << c.n_envs << "}\n"
                      << "algo: {id: " << c.algo << ", " << c.algo_settings << "}\n";
  return path;
}

}  // namespace

TEST_CASE("cli: 1, 2, 3 and 8 threads train bit-identical models", "[cli]") {
  TempDir dir("threads");
  // PPO (actor and critic side by side), DQN/TD3/SAC (a minibatch in parts) and PPO on four
  // LunarLanders (Box2D copies stepped on the pool once a batch is worth it).
  const Case cases[] = {
      {"ppo", "PPO", "CartPole-v1", 2, "n_steps: 128, batch_size: 64, n_epochs: 3"},
      {"dqn", "DQN", "CartPole-v1", 2, "learning_starts: 200, batch_size: 64"},
      {"td3", "TD3", "Pendulum-v1", 2, "learning_starts: 200, batch_size: 64"},
      {"sac", "SAC", "Pendulum-v1", 2, "learning_starts: 200, batch_size: 64"},
      {"ppo_lander", "PPO", "LunarLander-v3", 4, "n_steps: 64, batch_size: 64, n_epochs: 2"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string config = write_config(dir, c);
    const std::string base = dir / ("runs/" + std::string(c.name) + "/seed4");
    int run = 0;
    for (const char* threads : {"1", "2", "3", "8"}) {
      INFO(threads << " threads");
      const auto r = run_rlrun("--threads " + std::string(threads) + " train " + config);
      INFO(r.output);
      REQUIRE(r.exit_code == 0);
      const std::string said =
          std::string(threads) == "1" ? "1 thread)" : std::string(threads) + " threads)";
      CHECK(r.output.find(said) != std::string::npos);
      // Runs of one name go to seed4, seed4_2, seed4_3, ...
      if (++run > 1)
        check_same_tensors(base + "/model.zip", base + "_" + std::to_string(run) + "/model.zip");
    }
  }
}

TEST_CASE("cli: --threads auto uses the CPUs this process may use", "[cli]") {
  TempDir dir("threads_auto");
  const Case c{"auto", "PPO", "CartPole-v1", 1, "n_steps: 64, batch_size: 64, n_epochs: 1"};
  const std::string config = write_config(dir, c);
  // taskset (util-linux) pins rlrun to one CPU this process may use (not always CPU 0 in a
  // container): auto is then 1, whatever the machine has.
  cpu_set_t allowed;
  REQUIRE(sched_getaffinity(0, sizeof(allowed), &allowed) == 0);
  int cpu = 0;
  while (cpu < CPU_SETSIZE && !CPU_ISSET(cpu, &allowed)) ++cpu;
  const std::string pin = "taskset -c " + std::to_string(cpu) + " ";
  const auto pinned = run_command(pin + std::string(RLRUN_BINARY) + " --threads auto train " +
                                  config + " --timesteps 64");
  INFO(pinned.output);
  REQUIRE(pinned.exit_code == 0);
  CHECK(pinned.output.find("1 env, 1 thread)") != std::string::npos);
  const auto from_env = run_command(pin + "env RLRUN_THREADS=auto " + std::string(RLRUN_BINARY) +
                                    " train " + config + " --timesteps 64");
  INFO(from_env.output);
  REQUIRE(from_env.exit_code == 0);
  CHECK(from_env.output.find("1 env, 1 thread)") != std::string::npos);
}

TEST_CASE("cli: a thread count that is not a whole number from 1 or auto is a usage error",
          "[cli]") {
  for (const char* bad : {"0", "two", "1.5", "5000"}) {
    INFO(bad);
    const auto flag = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                                "/configs/cartpole_ppo.yaml --threads " + bad);
    CHECK(flag.exit_code == 2);
    CHECK(flag.output.find("--threads must be a whole number from 1 to 4096 or auto") !=
          std::string::npos);
  }
  const auto env = run_command("RLRUN_THREADS=many " + std::string(RLRUN_BINARY) + " list");
  CHECK(env.exit_code == 2);
  CHECK(env.output.find("RLRUN_THREADS must be a whole number from 1 to 4096 or auto") !=
        std::string::npos);
  CHECK(env.output.find("got 'many'") != std::string::npos);
}
