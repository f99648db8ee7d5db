// rl-zoo's policy_kwargs forms (net_arch {pi, vf} / {pi, qf}, torch activation classes,
// ortho_init false) through every path that rebuilds a model from its config.yaml: the run's
// resolved config, `rlrun eval`, ModelPolicy (the Python package's predict), `--init-from` and
// `--resume`. tests/python/test_predict.py checks the Python package on the same forms.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_policy.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct Case {
  std::string name, algo;  // algo: the YAML flow map of the algo section
  std::string resolved_arch, resolved_act;
  std::string tensor;  // a "<name> float32 (<shape>)" line numpy.load prints
};

void check_model_paths(const Case& c) {
  TempDir dir("policy_options_" + c.name);
  const std::string config = dir / (c.name + ".yaml");
  std::ofstream(config) << "run: {name: " << c.name
                        << ", seed: 1, total_timesteps: 256, out_dir: " << dir.str() << "}\n"
                        << "env: {id: Pendulum-v1}\n"
                        << "algo: " << c.algo << "\n"
                        << "checkpoint: {freq: 128}\n";
  const auto train = run_rlrun("--threads 1 train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run_dir = dir / (c.name + "/seed1");
  const std::string model = run_dir + "/model.zip";

  // The resolved config holds the canonical forms, so the model file reloads them.
  const std::string resolved = read_text(run_dir + "/config.yaml");
  CHECK(contains(resolved, "net_arch: " + c.resolved_arch));
  CHECK(contains(resolved, "activation_fn: " + c.resolved_act));
  const auto tensors = run_command("/usr/bin/python3 " + std::string(RLRUN_SOURCE_DIR) +
                                   "/tests/data/numpy_load_model.py " + model);
  INFO(tensors.output);
  CHECK(contains(tensors.output, c.tensor));

  // eval rebuilds the model from the file; ModelPolicy (Python's predict) gives its actions.
  const std::string steps = dir / "steps.csv";
  const auto eval =
      run_rlrun("eval --model " + model + " --episodes 1 --seed 3 --trajectory " + steps);
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  ModelPolicy policy(model, builtin_registry());
  std::ifstream in(steps);
  std::string line;
  std::getline(in, line);  // episode,step,obs_0,obs_1,obs_2,action_0,reward,...
  int rows = 0;
  Eigen::MatrixXf obs(3, 1), action;
  while (std::getline(in, line)) {
    std::vector<float> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(std::stof(cell));
    REQUIRE(cells.size() == 9);
    obs << cells[2], cells[3], cells[4];
    policy.predict(obs, /*deterministic=*/true, action);
    REQUIRE(action(0, 0) == cells[5]);
    ++rows;
  }
  CHECK(rows == 200);

  // Fine-tuning from the model, and resuming the run from its last checkpoint.
  const auto tuned = run_rlrun("--threads 1 train " + config + " --timesteps 128 --out " +
                               dir / "tuned" + " --init-from " + model);
  INFO(tuned.output);
  CHECK(tuned.exit_code == 0);
  CHECK(contains(tuned.output, "initialised from " + model));
  const auto resumed =
      run_rlrun("--threads 1 train --resume " + run_dir + " --set run.total_timesteps=384");
  INFO(resumed.output);
  CHECK(resumed.exit_code == 0);
  CHECK(contains(resumed.output, "(256 -> 384)"));
}

}  // namespace

TEST_CASE("cli: PPO with net_arch {pi, vf}, nn.ELU, ortho_init false through every reload path",
          "[cli][policy_options]") {
  check_model_paths({"ppo_arch",
                     "{id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1, policy: {net_arch: {pi: "
                     "[32], vf: [64, 64]}, activation_fn: nn.ELU, ortho_init: false}}",
                     "{pi: [32], vf: [64, 64]}", "elu",
                     "mlp_extractor.value_net.2.weight float32 (64, 64)"});
}

TEST_CASE("cli: SAC with net_arch {pi, qf}, nn.LeakyReLU through every reload path",
          "[cli][policy_options]") {
  check_model_paths({"sac_arch",
                     "{id: SAC, learning_starts: 64, batch_size: 32, policy: {net_arch: {pi: [64], "
                     "qf: [400, 300]}, activation_fn: nn.LeakyReLU}}",
                     "{pi: [64], qf: [400, 300]}", "leaky_relu",
                     "critic.qf1.2.weight float32 (300, 400)"});
}
