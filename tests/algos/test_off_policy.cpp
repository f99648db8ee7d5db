// The replay buffer and the shared off-policy loop (src/rlrun/algos/common/replay_buffer.*,
// off_policy.*) against SB3 2.x: common/buffers.py ReplayBuffer (terminal observations, dones
// without timeouts, uniform sampling over the filled part, circular overwrite) and
// common/off_policy_algorithm.py (warm-up while num_timesteps < learning_starts, training
// once num_timesteps > learning_starts, gradient_steps -1 = env steps collected, train_freq
// in steps or episodes). Tagged [dqn] too: DQN is the loop's main user.
#include <catch2/catch.hpp>
#include <memory>
#include <utility>
#include <vector>

#include "fakes/constant_env.hpp"
#include "fakes/counter_env.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/env/vec_env.hpp"

using namespace rlrun;

namespace {

VecEnv counter_vec_env(std::vector<int> lengths, uint64_t seed) {
  std::vector<EnvPtr> envs;
  for (int length : lengths) envs.push_back(std::make_unique<testing::CounterEnv>(length));
  VecEnv vec(std::move(envs));
  vec.seed(seed);
  return vec;
}

VecEnv constant_vec_env(int n_envs, bool truncate, int episode_length) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n_envs; ++i)
    envs.push_back(std::make_unique<fakes::ConstantEnv>(truncate, episode_length));
  return VecEnv(std::move(envs));
}

}  // namespace

TEST_CASE("ReplayBuffer stores the terminal observation, not the reset one, as next_obs",
          "[algos][replay][dqn]") {
  // CounterEnv: obs = start + steps since reset, start = the reset seed (10), then start + 100
  // on the automatic reset; the episode terminates after 2 steps.
  VecEnv env = counter_vec_env({2}, 10);
  ReplayBuffer buffer(/*buffer_size=*/12, /*n_envs=*/1, /*obs_dim=*/1, /*act_dim=*/1);
  Eigen::MatrixXf obs = env.reset();
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Constant(1, 1, 0.5f);
  for (int t = 0; t < 4; ++t) {  // 10 -> 11, 11 -> 12 (terminal), 110 -> 111, 111 -> 112
    env.step(actions);
    buffer.add(obs, actions, env);
    obs = env.obs();
  }
  REQUIRE(buffer.size() == 4);
  Rng rng(4);
  ReplayBatch batch;
  buffer.sample(400, rng, batch);
  int seen_terminal_0 = 0, seen_terminal_1 = 0;
  for (int j = 0; j < 400; ++j) {
    const float o = batch.obs(0, j), next = batch.next_obs(0, j);
    // Both episodes end here; next_obs is SB3's infos["terminal_observation"], never the
    // first observation of the next episode (110 after the first).
    const bool terminal = o == 11.0f || o == 111.0f;
    CHECK(next == o + 1.0f);
    CHECK(batch.dones(j) == (terminal ? 1.0f : 0.0f));
    if (o == 11.0f) ++seen_terminal_0;
    if (o == 111.0f) ++seen_terminal_1;
    CHECK(batch.rewards(j) == 0.5f);  // CounterEnv rewards the action
  }
  CHECK(seen_terminal_0 > 0);
  CHECK(seen_terminal_1 > 0);
}

TEST_CASE("ReplayBuffer: dones are terminations only when handling timeouts",
          "[algos][replay][dqn]") {
  for (bool handle : {true, false}) {
    VecEnv env = constant_vec_env(1, /*truncate=*/true, 2);
    ReplayBuffer buffer(8, 1, 1, 1, handle);
    Eigen::MatrixXf obs = env.reset();
    const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, 1);
    for (int t = 0; t < 4; ++t) {
      env.step(actions);
      buffer.add(obs, actions, env);
      obs = env.obs();
    }
    Rng rng(1);
    ReplayBatch batch;
    buffer.sample(200, rng, batch);
    // Every second transition is a time-limit truncation: done only without timeout handling
    // (SB3: dones * (1 - timeouts)).
    const float max_done = batch.dones.maxCoeff();
    CHECK(max_done == (handle ? 0.0f : 1.0f));
  }
}

TEST_CASE("ReplayBuffer samples the filled slots only and overwrites the oldest when full",
          "[algos][replay][dqn]") {
  VecEnv env = counter_vec_env({1000}, 0);  // obs 0, 1, 2, ... within one long episode
  ReplayBuffer buffer(5, 1, 1, 1);
  Eigen::MatrixXf obs = env.reset();
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, 1);
  Rng rng(2);
  ReplayBatch batch;
  for (int t = 0; t < 3; ++t) {
    env.step(actions);
    buffer.add(obs, actions, env);
    obs = env.obs();
  }
  CHECK(buffer.size() == 3);
  buffer.sample(300, rng, batch);
  CHECK(batch.obs.minCoeff() == 0.0f);  // randint(0, pos): every stored slot, no other
  CHECK(batch.obs.maxCoeff() == 2.0f);
  for (int t = 3; t < 8; ++t) {  // 8 transitions into 5 slots: obs 3..7 remain
    env.step(actions);
    buffer.add(obs, actions, env);
    obs = env.obs();
  }
  CHECK(buffer.size() == 5);
  buffer.sample(300, rng, batch);
  CHECK(batch.obs.minCoeff() == 3.0f);
  CHECK(batch.obs.maxCoeff() == 7.0f);
}

namespace {
struct LoopTrace {
  std::vector<std::pair<int64_t, bool>> actions;  // (num_timesteps before the step, warmup)
  std::vector<std::pair<int64_t, int>> trains;    // (num_timesteps, gradient_steps)
  int on_steps = 0;
};

// An off-policy algorithm that only records what the loop asks of it.
class LoopProbe : public OffPolicyAlgorithm {
 public:
  LoopProbe(const OffPolicyConfig& config, const AlgorithmSetup& setup, LoopTrace& trace)
      : OffPolicyAlgorithm("LoopProbe", config, setup, 1, {0, "replay_rng"},
                           /*normalize_images=*/true),
        trace_(trace) {}
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override {
    trace_.actions.emplace_back(num_timesteps(), warmup);
    env_actions = Eigen::MatrixXf::Zero(1, obs.cols());
    buffer_actions = env_actions;
  }
  void predict(const Eigen::Ref<const Eigen::MatrixXf>&, bool, Eigen::MatrixXf&) override {}
  void save(TensorMap&) const override {}
  void load(const TensorMap&) override {}

 private:
  void train(int gradient_steps, Logger*) override {
    trace_.trains.emplace_back(num_timesteps(), gradient_steps);
  }
  void on_step(Logger*) override { ++trace_.on_steps; }
  LoopTrace& trace_;
};

LoopTrace run_loop(OffPolicyConfig config, int n_envs, int episode_length, int64_t total) {
  VecEnv env = constant_vec_env(n_envs, /*truncate=*/false, episode_length);
  LoopTrace trace;
  LoopProbe probe(config, {env.observation_space(), env.action_space(), n_envs, 1}, trace);
  TrainingHooks hooks;
  probe.learn(env, total, hooks);
  CHECK(probe.num_timesteps() >= total);
  return trace;
}
}  // namespace

TEST_CASE("OffPolicyAlgorithm::learn: warm-up below learning_starts, training strictly above it",
          "[algos][off_policy][dqn]") {
  OffPolicyConfig config;
  config.buffer_size = 100;
  config.learning_starts = 6;
  config.train_freq = TrainFreq{3, false};  // 3 VecEnv steps = 6 env steps per rollout
  config.gradient_steps = -1;
  const LoopTrace trace = run_loop(config, /*n_envs=*/2, /*episode_length=*/5, 24);
  REQUIRE(trace.actions.size() == 12);
  // SB3 _sample_action: random while num_timesteps < learning_starts.
  for (const auto& [steps, warmup] : trace.actions) CHECK(warmup == (steps < 6));
  CHECK(trace.on_steps == 12);
  // After the first rollout num_timesteps == 6 == learning_starts: no training yet (SB3:
  // num_timesteps > learning_starts). Then gradient_steps -1 = the rollout's env steps
  // (num_collected_steps * n_envs).
  const std::vector<std::pair<int64_t, int>> expected{{12, 6}, {18, 6}, {24, 6}};
  CHECK(trace.trains == expected);
}

TEST_CASE("OffPolicyAlgorithm::learn: fixed gradient_steps, 0 skips training, episodic train_freq",
          "[algos][off_policy][dqn]") {
  OffPolicyConfig config;
  config.buffer_size = 100;
  config.learning_starts = 0;
  config.train_freq = TrainFreq{4, false};
  config.gradient_steps = 2;
  {
    const LoopTrace trace = run_loop(config, 1, 5, 10);  // rollouts end at 4, 8, 12
    const std::vector<std::pair<int64_t, int>> expected{{4, 2}, {8, 2}, {12, 2}};
    CHECK(trace.trains == expected);
  }
  config.gradient_steps = 0;
  CHECK(run_loop(config, 1, 5, 10).trains.empty());
  // [2, episode] with episodes of 3 steps: a rollout is 6 steps; -1 trains 6 steps.
  config.train_freq = TrainFreq{2, true};
  config.gradient_steps = -1;
  const LoopTrace trace = run_loop(config, 1, 3, 12);
  const std::vector<std::pair<int64_t, int>> expected{{6, 6}, {12, 6}};
  CHECK(trace.trains == expected);
}
