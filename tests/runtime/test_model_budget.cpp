// runtime/io/model_budget.hpp: real checkpoints of every algorithm — replay buffers full, obs_log
// rows pending, normalisation statistics, several envs — fit the budget derived from their
// config, and the budget is not much more than the file (plus the documented slack).
#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>

#include "fakes/constant_env.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_budget.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

// What read_model_tensors charges for the file's `.npy` members.
uint64_t file_charge(const std::string& path, bool with_training_state) {
  const ZipReader archive(path);
  uint64_t total = 0;
  for (const ZipEntry& e : archive.entries()) {
    const bool npy = e.name.size() > 4 && e.name.compare(e.name.size() - 4, 4, ".npy") == 0;
    if (!npy || (!with_training_state && e.name.rfind(kTrainingStatePrefix, 0) == 0)) continue;
    total += tensor_member_charge(e.name.size(), e.size);
  }
  return total;
}

}  // namespace

TEST_CASE("model budget: real checkpoints of every algorithm fit, with little to spare",
          "[runtime][budget]") {
  struct Case {
    const char* config;
    const char* settings;
  };
  // Buffers smaller than the run, so they are full; obs_log leaves rows pending.
  const std::vector<Case> cases{
      {"pendulum_sac.yaml", "algo.buffer_size=300 algo.learning_starts=50 env.n_envs=2"},
      {"pendulum_td3.yaml", "algo.buffer_size=300 algo.learning_starts=50"},
      {"gridworld_dqn.yaml", "algo.buffer_size=301 algo.learning_starts=50 env.n_envs=3"},
      {"cartpole_dqn.yaml", "algo.buffer_size=200 algo.learning_starts=50 env.n_envs=4"},
      {"cartpole_ppo.yaml", "env.n_envs=4"},
      {"cartpole_a2c.yaml", "env.n_envs=2"},
  };
  Registry registry = make_builtin_registry();
  for (const Case& c : cases) {
    TempDir dir("budget");
    std::string command = "train " + std::string(RLRUN_SOURCE_DIR) + "/configs/" + c.config +
                          " --set run.out_dir=" + dir.str() +
                          " --set run.total_timesteps=600 --set checkpoint.freq=500"
                          " --set obs_log.freq=400 --set eval.freq=0";
    std::stringstream settings(c.settings);
    for (std::string s; settings >> s;) command += " --set " + s;
    const auto r = run_rlrun(command);
    INFO(c.config << ": " << r.output);
    REQUIRE(r.exit_code == 0);
    std::string run_dir;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.str()))
      if (entry.path().filename() == "config.yaml") run_dir = entry.path().parent_path().string();
    REQUIRE(!run_dir.empty());
    std::string checkpoint;
    for (const auto& entry : std::filesystem::directory_iterator(run_dir + "/checkpoints"))
      checkpoint = entry.path().string();
    const Experiment experiment = load_experiment(run_dir + "/config.yaml", {}, registry);
    const uint64_t budget = checkpoint_tensor_budget(experiment, registry);
    const uint64_t charge = file_charge(checkpoint, true);
    const uint64_t slack = kCheckpointSlackBytes + kModelSlackBytes +
                           kCheckpointSlackPerEnvBytes * experiment.env.section.n_envs;
    INFO(c.config << ": budget " << budget << ", file " << charge << ", slack " << slack);
    CHECK(charge <= budget);
    CHECK(budget - slack <= charge + charge / 2 + 64 * 1024);
    CHECK_NOTHROW(read_checkpoint(checkpoint, experiment, registry));
    WARN(c.config << ": budget " << budget - slack << " + slack, file " << charge);
  }
}

TEST_CASE("model budget: a full replay buffer's state is what replay_buffer_growth adds",
          "[runtime][budget]") {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < 2; ++i) envs.push_back(std::make_unique<fakes::ConstantEnv>(false, 7));
  VecEnv env(std::move(envs));
  ReplayBuffer buffer(/*buffer_size=*/50, /*n_envs=*/2, /*obs_dim=*/1, /*act_dim=*/3);
  TensorMap fresh;
  buffer.write_state(StateWriter(fresh, "training/algo/off_policy/replay_buffer/"));
  Eigen::MatrixXf obs = env.reset();
  const Eigen::MatrixXf env_actions = Eigen::MatrixXf::Zero(1, 2);
  const Eigen::MatrixXf buffer_actions = Eigen::MatrixXf::Constant(3, 2, 0.5f);
  for (int t = 0; t < 60; ++t) {
    env.step(env_actions);
    buffer.add(obs, buffer_actions, env);
    obs = env.obs();
  }
  REQUIRE(buffer.size() == buffer.capacity());
  TensorMap full;
  buffer.write_state(StateWriter(full, "training/algo/off_policy/replay_buffer/"));
  uint64_t fresh_bytes = 0, full_bytes = 0;
  for (const auto& [key, t] : fresh) fresh_bytes += t.bytes.size();
  for (const auto& [key, t] : full) full_bytes += t.bytes.size();
  // obs, next_obs (1 row), actions (3 rows), rewards, dones: 7 floats per transition.
  CHECK(replay_buffer_growth(fresh) == 50u * 7 * sizeof(float));
  CHECK(fresh_bytes + replay_buffer_growth(fresh) == full_bytes);
  CHECK(tensor_map_charge(fresh) + replay_buffer_growth(fresh) >= tensor_map_charge(full));
}
