// --threads / RLRUN_THREADS: the second core changes the speed of a run, never its result.
#include <catch2/catch.hpp>
#include <fstream>

#include "runtime/cli_runner.hpp"
#include "runtime/same_tensors.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {
std::string write_config(const TempDir& dir, const std::string& algo, const std::string& env) {
  const std::string path = dir / (algo + ".yaml");
  std::ofstream(path) << "run: {name: " << algo << ", seed: 4, total_timesteps: 1500, out_dir: "
                      << dir.str() << "/runs}\n"
                      << "env: {id: " << env << ", n_envs: 2}\n"
                      << "algo: {id: " << algo << ", learning_starts: 200, batch_size: 64}\n";
  return path;
}
}  // namespace

TEST_CASE("cli: one or two threads train bit-identical models", "[cli]") {
  TempDir dir("threads");
  // PPO (actor and critic on two cores) and DQN/TD3/SAC (minibatch split over two cores).
  for (const auto& [algo, env] : {std::pair{"PPO", "CartPole-v1"}, {"DQN", "CartPole-v1"},
                                  {"TD3", "Pendulum-v1"}, {"SAC", "Pendulum-v1"}}) {
    INFO(algo);
    std::string config = write_config(dir, algo, env);
    if (std::string(algo) == "PPO")  // PPO has no replay-buffer keys
      std::ofstream(config) << "run: {name: PPO, seed: 4, total_timesteps: 1500, out_dir: "
                            << dir.str() << "/runs}\nenv: {id: CartPole-v1, n_envs: 2}\n"
                            << "algo: {id: PPO, n_steps: 128, batch_size: 64, n_epochs: 3}\n";
    const auto one = run_rlrun("--threads 1 train " + config);
    INFO(one.output);
    REQUIRE(one.exit_code == 0);
    const auto two = run_rlrun("train " + config + " --threads 2");
    INFO(two.output);
    REQUIRE(two.exit_code == 0);
    check_same_tensors(dir / ("runs/" + std::string(algo) + "/seed4/model.zip"),
                       dir / ("runs/" + std::string(algo) + "/seed4_2/model.zip"));
  }
}

TEST_CASE("cli: a thread count other than 1 or 2 is a usage error", "[cli]") {
  const auto flag = run_rlrun("list --threads 3");
  CHECK(flag.exit_code == 2);
  CHECK(flag.output.find("--threads: must be 1 or 2") != std::string::npos);
  const auto env = run_command("RLRUN_THREADS=many " + std::string(RLRUN_BINARY) + " list");
  CHECK(env.exit_code == 2);
  CHECK(env.output.find("RLRUN_THREADS must be 1 or 2") != std::string::npos);
}
