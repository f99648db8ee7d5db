// How the replay buffer stores observations (src/rlrun/algos/common/observation_columns.*,
// replay_buffer.*): uint8 Boxes as bytes, as SB3's ReplayBuffer allocates its observations with
// the space's dtype, and SB3's optimize_memory_usage (stable_baselines3/common/buffers.py:
// the next observation is the following slot's, the slot being written is never sampled).
#include <catch2/catch.hpp>
#include <memory>
#include <utility>
#include <vector>

#include "fakes/counter_env.hpp"
#include "rlrun/algos/common/observation_columns.hpp"
#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/env/vec_env.hpp"

using namespace rlrun;

namespace {

VecEnv counter_vec_env(int n_envs, int length, uint64_t seed) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n_envs; ++i) envs.push_back(std::make_unique<testing::CounterEnv>(length));
  VecEnv vec(std::move(envs));
  vec.seed(seed);
  return vec;
}

// Runs `steps` VecEnv steps into `buffer`, the action of env e at step t being t * 10 + e.
void fill(ReplayBuffer& buffer, VecEnv& env, int steps) {
  Eigen::MatrixXf obs = env.reset();
  Eigen::MatrixXf actions(1, env.num_envs());
  for (int t = 0; t < steps; ++t) {
    for (int e = 0; e < env.num_envs(); ++e) actions(0, e) = static_cast<float>(t * 10 + e);
    env.step(actions);
    buffer.add(obs, actions, env);
    obs = env.obs();
  }
}

}  // namespace

TEST_CASE("ObservationColumns keeps uint8 Boxes as bytes and gives back the same floats",
          "[algos][replay][image]") {
  const Space space = Space::dict({{"pixels", Space::image({2, 2, 1})},
                                   {"state", Space::box(-10.0f, 10.0f, {2})},
                                   {"z_mask", Space::box(0.0f, 1.0f, {3}, BoxDtype::kUint8)}});
  // Sorted keys: pixels (4 bytes), state (2 floats), z_mask (3 bytes).
  CHECK(ObservationColumns::bytes_per_observation(space) == 4 + 2 * 4 + 3);
  CHECK(ObservationColumns::bytes_per_observation(Space::image({4, 84, 84})) == 28224);
  CHECK(ObservationColumns::bytes_per_observation(Space::box(0.0f, 1.0f, {5})) == 20);
  ObservationColumns columns(space, 3);
  REQUIRE(columns.rows() == 9);
  const std::vector<float> a{0, 17, 254, 255, -3.25f, 9.5f, 1, 0, 1};
  const std::vector<float> b{1, 2, 3, 4, 0.125f, -0.5f, 0, 0, 1};
  columns.set(0, a.data());
  columns.set(2, b.data());
  std::vector<float> out(9);
  columns.get(0, out.data());
  CHECK(out == a);
  columns.get(2, out.data());
  CHECK(out == b);
  // A range across the float and byte stretches (HER reads goals this way).
  std::vector<float> part(4);
  columns.get(0, 3, 4, part.data());
  CHECK(part == std::vector<float>{255, -3.25f, 9.5f, 1});
}

TEST_CASE("ReplayBuffer with uint8 observations samples what a float32 one does",
          "[algos][replay][image]") {
  // Episodes of 7 steps from 3 and 4, then from 103 / 104 and 203 / 204: all within a byte.
  VecEnv env_bytes = counter_vec_env(2, 7, 3), env_floats = counter_vec_env(2, 7, 3);
  ReplayBuffer bytes(20, 2, Space::image({1}), 1), floats(20, 2, 1, 1);
  fill(bytes, env_bytes, 16);  // wraps around: 10 slots per env
  fill(floats, env_floats, 16);
  Rng rng_a(9), rng_b(9);
  ReplayBatch a, b;
  bytes.sample(64, rng_a, a);
  floats.sample(64, rng_b, b);
  CHECK(a.obs == b.obs);
  CHECK(a.next_obs == b.next_obs);
  CHECK(a.actions == b.actions);
  CHECK(a.dones == b.dones);
}

TEST_CASE("ReplayBuffer optimize_memory_usage: the next observation is the following slot's",
          "[algos][replay][dqn]") {
  CHECK_THROWS_WITH(ReplayBuffer(10, 1, Space::image({1}), 1, /*handle_timeout=*/true, true),
                    Catch::Contains("handle_timeout_termination: false"));
  CHECK_THROWS_WITH(ReplayBuffer(3, 2, Space::image({1}), 1, false, true),
                    Catch::Contains("two transitions per env"));
  for (const int n_envs : {1, 2}) {
    // Episodes of 1000 steps; env e starts at obs e (seed 0 + e): obs t + e -> t + e + 1.
    const float last_env = static_cast<float>(n_envs - 1);
    VecEnv env = counter_vec_env(n_envs, 1000, 0);
    ReplayBuffer buffer(6 * n_envs, n_envs, Space::image({1}), 1, false, true);
    Rng rng(5);
    ReplayBatch batch;
    fill(buffer, env, 4);
    buffer.sample(300, rng, batch);  // randint(0, pos): slots 0-3, their next obs in slots 1-4
    CHECK(batch.obs.minCoeff() == 0.0f);
    CHECK(batch.obs.maxCoeff() == 3.0f + last_env);
    CHECK(batch.next_obs == (batch.obs.array() + 1.0f).matrix());
    // 13 transitions into 6 slots: slot 0 holds t = 12, slots 2-5 t = 8-11, and slot 1 (pos,
    // being written) t = 7's action with obs 13, t = 12's next observation. SB3 samples every
    // slot but pos.
    VecEnv more = counter_vec_env(n_envs, 1000, 0);
    ReplayBuffer full(6 * n_envs, n_envs, Space::image({1}), 1, false, true);
    fill(full, more, 13);
    full.sample(600, rng, batch);
    CHECK(batch.obs.minCoeff() == 8.0f);
    CHECK(batch.obs.maxCoeff() == 12.0f + last_env);
    CHECK(batch.next_obs == (batch.obs.array() + 1.0f).matrix());
    for (int j = 0; j < batch.actions.cols(); ++j) {  // action t * 10 + e stored with obs t + e
      const int action = static_cast<int>(batch.actions(0, j)), e = action % 10;
      CHECK(action / 10 == static_cast<int>(batch.obs(0, j)) - e);
    }
  }
}

TEST_CASE("ReplayBuffer optimize_memory_usage: episode ends are done, the reset obs follows",
          "[algos][replay][dqn]") {
  // CounterEnv(3) seeded 10: 10 11 12 | 110 111 112 | ...; terminations are dones (no timeout
  // handling), so a terminal transition's next obs (the reset obs here) is never bootstrapped.
  VecEnv env = counter_vec_env(1, 3, 10);
  ReplayBuffer buffer(20, 1, Space::box(-1e9f, 1e9f, {1}), 1, false, true);
  fill(buffer, env, 7);
  Rng rng(3);
  ReplayBatch batch;
  buffer.sample(400, rng, batch);
  for (int j = 0; j < 400; ++j) {
    const float o = batch.obs(0, j);
    const bool terminal = o == 12.0f || o == 112.0f;
    CHECK(batch.dones(j) == (terminal ? 1.0f : 0.0f));
    if (!terminal) CHECK(batch.next_obs(0, j) == o + 1.0f);
  }
}

TEST_CASE("ReplayBuffer checkpoints keep uint8 observations as bytes and resume exactly",
          "[algos][replay][image]") {
  for (const bool optimize : {false, true}) {
    VecEnv env = counter_vec_env(2, 5, 1);
    ReplayBuffer buffer(16, 2, Space::image({1}), 1, !optimize, optimize);
    fill(buffer, env, 5);  // not full: with optimize the slot after the last is stored too
    TensorMap tensors;
    buffer.write_state(StateWriter(tensors, "b/"));
    REQUIRE(tensors.count("b/obs_uint8") == 1);
    CHECK(tensors.at("b/obs_uint8").dtype == DType::kUInt8);
    CHECK(tensors.at("b/obs_uint8").shape[1] == (optimize ? 12 : 10));
    CHECK(tensors.count("b/obs") == 0);
    CHECK(tensors.count("b/next_obs_uint8") == (optimize ? 0u : 1u));
    ReplayBuffer restored(16, 2, Space::image({1}), 1, !optimize, optimize);
    restored.read_state(StateReader(tensors, "b/"));
    Rng rng_a(4), rng_b(4);
    ReplayBatch a, b;
    buffer.sample(50, rng_a, a);
    restored.sample(50, rng_b, b);
    CHECK(a.obs == b.obs);
    CHECK(a.next_obs == b.next_obs);
    CHECK(a.actions == b.actions);
  }
}

TEST_CASE("RolloutBuffer keeps uint8 observations as bytes too", "[algos][image][ppo]") {
  // 4 steps x 2 envs of 84x84x4 frames: 225 KB as bytes, where SB3's float32 rollout takes 903 KB.
  const RolloutBuffer images(4, 2, Space::image({84, 84, 4}), 1);
  CHECK(images.obs.bytes() == 8 * 28224);
  CHECK(images.size() == 8);
  const RolloutBuffer vectors(4, 2, Space::box(-1.0f, 1.0f, {3}), 1);
  CHECK(vectors.obs.bytes() == 8 * 3 * 4);
}
