// MaskablePPO and action masks (sb3-contrib 2.4's semantics; src/rlrun/algos/ppo_mask/,
// nn/action_masking.hpp, env/action_mask.hpp): the masked distribution against hand-computed
// values and finite differences, masked actions never drawn, the rollout buffer's masks,
// exact resume, checked checkpoints, GridWorld's mask, and the errors for bad masks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/algos/ppo_mask/ppo_mask.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/envs/grid_world/grid_world.hpp"
#include "rlrun/nn/action_masking.hpp"
#include "rlrun/nn/categorical.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/run/evaluator.hpp"

using namespace rlrun;

namespace {

VecEnv grid_envs(int n, uint64_t seed) {
  EnvSpec spec = default_env_spec("GridWorld-v0", builtin_registry(), "test");
  VecEnv env = make_vec_env(spec, builtin_registry(), n, "");
  env.seed(seed);
  return env;
}

// GridWorld's mask for an observation (row, col) of a size x size grid: the moves that stay on
// it (up, right, down, left).
Eigen::Vector4f grid_mask(float row, float col, int size = 5) {
  return {row > 0 ? 1.0f : 0.0f, col < size - 1 ? 1.0f : 0.0f, row < size - 1 ? 1.0f : 0.0f,
          col > 0 ? 1.0f : 0.0f};
}

// A Discrete(4) env whose mask (info action_mask.*) the test sets: `length` entries, all 0 at
// step `empty_at` of its life, else action 0 and 2 legal (or `value` in place of each 1).
class MaskedEnv : public Env {
 public:
  MaskedEnv(int length, int empty_at = -1, float value = 1.0f)
      : length_(length), empty_at_(empty_at), value_(value) {
    for (int k = 0; k < length; ++k) keys_.push_back(info_.add_key(action_mask_key(k)));
  }
  const Space& observation_space() const override { return obs_space_; }
  const Space& action_space() const override { return act_space_; }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    obs[0] = 0.0f;
    write_mask();
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    obs[0] = 0.0f;
    ++steps_;
    illegal_ += action[0] == 1.0f || action[0] == 3.0f;
    write_mask();
    return {1.0, false, steps_ % 7 == 0};
  }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Masked-v0"; }
  int illegal() const { return illegal_; }

 private:
  void write_mask() {
    info_.clear();
    for (int k = 0; k < length_; ++k)
      info_.set(keys_[k], steps_ == empty_at_ ? 0.0 : (k % 2 == 0 ? value_ : 0.0));
  }
  int length_, empty_at_;
  float value_;
  int steps_ = 0, illegal_ = 0;
  std::vector<int> keys_;
  Space obs_space_ = Space::box(-1.0f, 1.0f, {1});
  Space act_space_ = Space::discrete(4);
  Info info_;
};

// Three agents with Discrete(3) actions; agent a may take only action a (its mask is
// action_mask.<3a> ... action_mask.<3a + 2>, agent-major).
class MaskedAgentsEnv : public Env {
 public:
  MaskedAgentsEnv() {
    for (int k = 0; k < 9; ++k) info_.set(info_.add_key(action_mask_key(k)), k % 4 == 0);
  }
  int num_agents() const override { return 3; }
  const Space& observation_space() const override { return obs_space_; }
  const Space& action_space() const override { return act_space_; }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    std::fill(obs.begin(), obs.end(), 0.0f);
  }
  StepResult step(std::span<const float>, std::span<float>) override {
    throw std::logic_error("several agents");
  }
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override {
    const bool end = ++steps_ % 30 == 0;
    for (int a = 0; a < 3; ++a) {
      illegal_ += actions[a] != static_cast<float>(a);
      results[a] = {1.0, false, end};
    }
    reset(std::nullopt, obs);
  }
  const Info& info() const override { return info_; }
  std::string id() const override { return "MaskedAgents-v0"; }
  int illegal() const { return illegal_; }

 private:
  int illegal_ = 0, steps_ = 0;
  Space obs_space_ = Space::box(-1.0f, 1.0f, {1});
  Space act_space_ = Space::discrete(3);
  Info info_;
};

VecEnv masked_envs(int n, int length, int empty_at = -1, float value = 1.0f) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n; ++i) envs.push_back(std::make_unique<MaskedEnv>(length, empty_at, value));
  return VecEnv(std::move(envs));
}

MaskablePPO::Config small_config() {
  MaskablePPO::Config cfg;
  cfg.n_steps = 32;
  cfg.batch_size = 16;
  cfg.n_epochs = 2;
  cfg.policy.net_arch = {{16}, {16}};
  return cfg;
}

// A random 0/1 mask for each column with at least one 1 in each categorical part.
Eigen::MatrixXf random_masks(const std::vector<int64_t>& parts, int n, Rng& rng) {
  int64_t rows = 0;
  for (int64_t p : parts) rows += p;
  Eigen::MatrixXf masks(rows, n);
  for (int j = 0; j < n; ++j) {
    int64_t at = 0;
    for (int64_t p : parts) {
      for (int64_t i = 0; i < p; ++i) masks(at + i, j) = rng.uniform() < 0.5 ? 1.0f : 0.0f;
      masks(at + static_cast<int64_t>(rng.below(static_cast<uint64_t>(p))), j) = 1.0f;
      at += p;
    }
  }
  return masks;
}

// (a, b) weights of log p(action) and H in the test loss L = sum_j a log p + b H.
constexpr double kA = 0.7, kB = -0.3;

double masked_loss(const Eigen::MatrixXf& logits, const Eigen::MatrixXf& masks,
                   const Eigen::RowVectorXf& actions) {
  Categorical dist;
  dist.set_logits(logits, masks);
  Eigen::RowVectorXf lp(actions.size()), h(actions.size());
  dist.log_prob(actions, lp);
  dist.entropy(h);
  return kA * lp.cast<double>().sum() + kB * h.cast<double>().sum();
}

}  // namespace

TEST_CASE("masked categorical: log-prob, entropy and gradient equal hand-computed values",
          "[algos][ppo_mask]") {
  // Two columns; the second masks the largest logit.
  Eigen::MatrixXf logits(4, 2), masks(4, 2);
  logits.col(0) << 1.0f, 2.0f, 3.0f, 0.5f;
  logits.col(1) << -2.0f, 0.1f, 0.2f, 4.0f;
  masks.col(0) << 1, 0, 1, 1;
  masks.col(1) << 0, 1, 1, 0;
  const Eigen::RowVectorXf actions = (Eigen::RowVectorXf(2) << 2, 1).finished();

  Eigen::MatrixXf masked;
  mask_logits(logits, masks, masked);
  CHECK(masked(1, 0) == -1e8f);
  Categorical dist;
  dist.set_logits(logits, masks);
  CHECK(dist.log_probs()(1, 0) < -9e7f);  // torch: the normalised -1e8
  Eigen::RowVectorXf lp(2), h(2);
  dist.log_prob(actions, lp);
  dist.entropy(h);
  Eigen::MatrixXf grad;
  dist.backward(actions, Eigen::RowVectorXf::Constant(2, static_cast<float>(kA)),
                Eigen::RowVectorXf::Constant(2, static_cast<float>(kB)), grad);
  mask_logit_gradient(masks, grad);

  for (int j = 0; j < 2; ++j) {
    // By hand, in double: a softmax over the legal logits only.
    double lse = 0;
    for (int i = 0; i < 4; ++i)
      if (masks(i, j) != 0) lse += std::exp(double(logits(i, j)));
    lse = std::log(lse);
    double entropy = 0;
    std::vector<double> p(4, 0.0);
    for (int i = 0; i < 4; ++i)
      if (masks(i, j) != 0) {
        p[i] = std::exp(double(logits(i, j)) - lse);
        entropy -= p[i] * std::log(p[i]);
      }
    const int a = static_cast<int>(actions(j));
    CHECK(lp(j) == Approx(double(logits(a, j)) - lse).epsilon(1e-6));
    CHECK(h(j) == Approx(entropy).epsilon(1e-6));
    for (int i = 0; i < 4; ++i) {
      INFO("column " << j << " logit " << i);
      // Masked: probability exactly 0, no gradient (th.where passes none).
      if (masks(i, j) == 0) {
        CHECK(dist.probs()(i, j) == 0.0f);
        CHECK(grad(i, j) == 0.0f);
        continue;
      }
      // d log p(a)/dz_i = 1[i = a] - p_i; dH/dz_i = -p_i (log p_i + H).
      const double expected =
          kA * ((i == a ? 1.0 : 0.0) - p[i]) + kB * (-p[i] * (std::log(p[i]) + entropy));
      CHECK(grad(i, j) == Approx(expected).epsilon(1e-5).margin(1e-6));
      // And the float implementation's own finite difference.
      Eigen::MatrixXf up = logits, down = logits;
      up(i, j) += 1e-2f;
      down(i, j) -= 1e-2f;
      const double numeric =
          (masked_loss(up, masks, actions) - masked_loss(down, masks, actions)) / 2e-2;
      CHECK(grad(i, j) == Approx(numeric).epsilon(1e-2).margin(1e-4));
    }
  }
}

TEST_CASE("MaskablePPO loss gradient through the masked policy matches finite differences",
          "[algos][ppo_mask][gradcheck]") {
  const Space action_space =
      GENERATE(Space::discrete(5), Space::multi_discrete({3, 2, 4}), Space::multi_binary(3));
  INFO(action_space.describe());
  const Space obs_space = Space::box(-1.0f, 1.0f, {3});
  Rng rng(5);
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{8, 8}, {8, 8}};
  ActorCriticPolicy policy(obs_space, action_space, cfg, rng, false, /*maskable=*/true);
  std::vector<int64_t> parts =
      action_space.is_discrete() ? std::vector<int64_t>{action_space.n()} : action_space.nvec();
  if (action_space.kind() == SpaceKind::kMultiBinary) parts.assign(3, 2);
  const int n = 16;
  const Eigen::MatrixXf obs = Eigen::MatrixXf::Random(3, n);
  const Eigen::MatrixXf masks = random_masks(parts, n, rng);
  Eigen::MatrixXf actions;
  Eigen::RowVectorXf values, log_probs;
  policy.act(obs, rng, false, actions, values, log_probs, &masks);
  Eigen::RowVectorXf old_log_prob = log_probs, old_values = values;
  for (int j = 0; j < n; ++j) old_log_prob(j) += (j % 2 ? 0.05f : -0.6f);
  const Eigen::RowVectorXf adv = Eigen::RowVectorXf::Random(n), ret = Eigen::RowVectorXf::Random(n);
  Eigen::RowVectorXf gv(n), gl(n), ge(n);
  auto loss = [&] {
    Eigen::RowVectorXf v, lp, h;
    policy.evaluate_actions(obs, actions, v, lp, h, &masks);
    return ppo_loss({v, lp, h, old_log_prob, old_values, adv, ret}, 0.2f, std::nullopt, 0.05f, 0.5f,
                    gv, gl, ge)
        .loss;
  };
  policy.zero_grad();
  loss();
  policy.backward(gv, gl, ge);
  int checked = 0;
  for (ParamBlock block : policy.param_blocks()) {
    for (Eigen::Index i = 0; i < block.size; i += 5) {
      const float saved = block.value[i];
      block.value[i] = saved + 1e-3f;
      const double up = loss();
      block.value[i] = saved - 1e-3f;
      const double down = loss();
      block.value[i] = saved;
      INFO("param " << i);
      CHECK(block.grad[i] == Approx((up - down) / 2e-3).epsilon(0.03).margin(5e-4));
      ++checked;
    }
  }
  CHECK(checked > 20);
}

TEST_CASE("a masked policy never samples nor picks a masked action", "[algos][ppo_mask]") {
  const Space action_space =
      GENERATE(Space::discrete(6), Space::multi_discrete({4, 3}), Space::multi_binary(4));
  INFO(action_space.describe());
  Rng rng(11);
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{8}, {8}};
  // ortho_init's 0.01 head gain makes the unmasked distribution nearly uniform: without the
  // masks, half the draws would be masked actions.
  ActorCriticPolicy policy(Space::box(-1.0f, 1.0f, {2}), action_space, cfg, rng, false, true);
  std::vector<int64_t> parts =
      action_space.is_discrete() ? std::vector<int64_t>{action_space.n()} : action_space.nvec();
  if (action_space.kind() == SpaceKind::kMultiBinary) parts.assign(4, 2);
  const int n = 500;
  const Eigen::MatrixXf obs = Eigen::MatrixXf::Random(2, n);
  const Eigen::MatrixXf masks = random_masks(parts, n, rng);
  for (const bool deterministic : {false, true}) {
    Eigen::MatrixXf actions;
    Eigen::RowVectorXf values, log_probs;
    policy.act(obs, rng, deterministic, actions, values, log_probs, &masks);
    int illegal = 0;
    for (int j = 0; j < n; ++j) {
      int64_t at = 0;
      for (size_t d = 0; d < parts.size(); ++d) {
        illegal +=
            masks(at + static_cast<int64_t>(actions(static_cast<Eigen::Index>(d), j)), j) == 0;
        at += parts[d];
      }
    }
    CHECK(illegal == 0);
    CHECK(log_probs.allFinite());
  }
}

TEST_CASE("GridWorld reports the moves that stay on the grid as its action mask",
          "[algos][ppo_mask][grid_world]") {
  GridWorld env;
  float obs[2];
  env.reset(1, obs);
  ActionMaskReader reader(env.action_space());
  Eigen::Vector4f mask;
  REQUIRE(reader.read(env.info(), 1, {mask.data(), 4}).empty());
  CHECK(mask == grid_mask(0, 0));  // (0, 0): only right and down
  const float down = GridWorld::kDown, right = GridWorld::kRight;
  for (int i = 0; i < 4; ++i) env.step({&down, 1}, obs);
  REQUIRE(reader.read(env.info(), 1, {mask.data(), 4}).empty());
  CHECK(mask == grid_mask(4, 0));
  env.step({&right, 1}, obs);
  REQUIRE(reader.read(env.info(), 1, {mask.data(), 4}).empty());
  CHECK(mask == (Eigen::Vector4f() << 1, 1, 0, 1).finished());
}

TEST_CASE("MaskablePPO's rollout buffer keeps the mask each action was drawn under",
          "[algos][ppo_mask]") {
  VecEnv env = grid_envs(3, 4);
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), 3, 4};
  Rng rng(4);
  ActorCriticPolicy policy(setup.observation_space, setup.action_space, {}, rng, false, true);
  OnPolicyCollector collector(setup, 40, policy.action_dim(), -1, policy.mask_size());
  TrainingHooks hooks;
  int64_t steps = 0;
  collector.start(env);
  FeedForwardRollout rollout(policy);
  REQUIRE(collector.collect(env, rollout, rng, 0.99f, 0.95f, hooks, steps));
  const RolloutBuffer& buffer = collector.buffer();
  REQUIRE(buffer.action_masks.rows() == 4);
  REQUIRE(buffer.action_masks.cols() == 120);
  for (int k = 0; k < buffer.size(); ++k) {
    float cell[2];
    buffer.obs.get(k, cell);
    INFO("sample " << k << " at (" << cell[0] << ", " << cell[1] << ")");
    CHECK(buffer.action_masks.col(k) == grid_mask(cell[0], cell[1]));
    CHECK(buffer.action_masks(static_cast<Eigen::Index>(buffer.actions(0, k)), k) == 1.0f);
  }
}

TEST_CASE("MaskablePPO resumed from a safe point ends with the uninterrupted run's weights",
          "[algos][ppo_mask][resume]") {
  const MaskablePPO::Config cfg = small_config();
  auto flatten = [](const MaskablePPO& algo) {
    TensorMap model;
    algo.save(model);
    std::vector<float> all;
    for (const auto& [name, tensor] : model)
      all.insert(all.end(), tensor.data<float>(), tensor.data<float>() + tensor.numel());
    return all;
  };
  TensorMap model, state;
  VecEnv env1 = grid_envs(2, 7);
  MaskablePPO uninterrupted(cfg, {env1.observation_space(), env1.action_space(), 2, 7});
  TrainingHooks hooks;
  int64_t saved_at = -1;
  hooks.at_safe_point = [&](int64_t steps) {
    if (saved_at < 0 && steps >= 300) {
      saved_at = steps;
      uninterrupted.save(model);
      StateWriter algo_out(state, "algo/");
      uninterrupted.save_training_state(algo_out);
      StateWriter env_out(state, "env/");
      env1.write_state(env_out);
    }
    return true;
  };
  uninterrupted.learn(env1, 1024, hooks);
  CHECK(saved_at == 320);

  VecEnv env2 = grid_envs(2, 7);
  MaskablePPO resumed(cfg, {env2.observation_space(), env2.action_space(), 2, 1007});
  resumed.load(model);
  resumed.load_training_state(StateReader(state, "algo/"));
  env2.read_state(StateReader(state, "env/"));
  TrainingHooks plain;
  resumed.learn(env2, 1024, plain);
  CHECK(resumed.num_timesteps() == 1024);
  CHECK(flatten(resumed) == flatten(uninterrupted));

  SECTION("a checkpoint's masks are checked as untrusted data") {
    std::string key;
    for (const auto& [name, tensor] : state)
      if (name.size() >= 10 && name.compare(name.size() - 10, 10, "last_masks") == 0) key = name;
    REQUIRE(!key.empty());
    const float bad = GENERATE(0.5f, 0.0f);
    INFO("entry value " << bad);
    float* masks = state[key].data<float>();
    for (int i = 0; i < 8; ++i) masks[i] = bad;  // not 0/1, or no legal move
    MaskablePPO fresh(cfg, {env2.observation_space(), env2.action_space(), 2, 1});
    CHECK_THROWS_WITH(fresh.load_training_state(StateReader(state, "algo/")),
                      Catch::Contains("last_masks") && Catch::Contains("env 0"));
  }
}

TEST_CASE("MaskablePPO takes only the actions the env's masks allow, in training and evaluation",
          "[algos][ppo_mask]") {
  VecEnv env = masked_envs(2, 4);
  MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 2, 3});
  TrainingHooks hooks;
  algo.learn(env, 256, hooks);
  for (int c = 0; c < 2; ++c) CHECK(static_cast<const MaskedEnv&>(env.env(c)).illegal() == 0);
  MaskedEnv eval_env(4);
  const EvalResult r = evaluate_policy(algo, eval_env, 5, false, 1);
  CHECK(r.returns.size() == 5);
  CHECK(eval_env.illegal() == 0);
  // The same algorithm without masks (sb3-contrib predict(action_masks=None)) is unmasked.
  Eigen::MatrixXf obs = Eigen::MatrixXf::Zero(1, 200), actions;
  algo.predict(obs, false, actions);
  CHECK((actions.array() == 1.0f || actions.array() == 3.0f).any());
  Eigen::MatrixXf masks = Eigen::MatrixXf::Zero(4, 200);
  masks.row(3).setOnes();
  algo.predict_masked(obs, masks, false, actions);
  CHECK((actions.array() == 3.0f).all());
}

TEST_CASE("a multi-agent env's masks are agent-major, one per column of the VecEnv",
          "[algos][ppo_mask]") {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < 2; ++i) envs.push_back(std::make_unique<MaskedAgentsEnv>());
  VecEnv env(std::move(envs));
  REQUIRE(env.num_envs() == 6);
  MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 6, 2});
  TrainingHooks hooks;
  algo.learn(env, 6 * 64, hooks);
  for (int c = 0; c < 2; ++c) CHECK(static_cast<const MaskedAgentsEnv&>(env.env(c)).illegal() == 0);
  MaskedAgentsEnv eval_env;
  CHECK(evaluate_policy(algo, eval_env, 2, false, 1).returns.size() == 2);
  CHECK(eval_env.illegal() == 0);
}

TEST_CASE("bad action masks stop MaskablePPO with the env and the step named",
          "[algos][ppo_mask]") {
  SECTION("no mask") {
    VecEnv env = masked_envs(1, 0);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 1, 1});
    TrainingHooks hooks;
    CHECK_THROWS_WITH(algo.learn(env, 64, hooks),
                      Catch::Contains("Masked-v0 (env 0) after reset()") &&
                          Catch::Contains("reports no action mask"));
  }
  SECTION("a mask of the wrong length") {
    VecEnv env = masked_envs(1, 5);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 1, 1});
    TrainingHooks hooks;
    CHECK_THROWS_WITH(algo.learn(env, 64, hooks),
                      Catch::Contains("an action mask of 5 entries, MaskablePPO needs 4"));
  }
  SECTION("a mask with no legal action") {
    VecEnv env = masked_envs(2, 4, 13);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 2, 1});
    TrainingHooks hooks;
    CHECK_THROWS_WITH(
        algo.learn(env, 640, hooks),
        Catch::Contains("Masked-v0 (env 0) at step 26") && Catch::Contains("allows no action"));
  }
  SECTION("a mask entry other than 0 and 1") {
    VecEnv env = masked_envs(1, 4, -1, 0.5f);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 1, 1});
    TrainingHooks hooks;
    CHECK_THROWS_WITH(algo.learn(env, 64, hooks), Catch::Contains("is 0.500000, not 0 or 1"));
  }
  SECTION("predict_masked refuses masks of another shape or with no legal action") {
    VecEnv env = masked_envs(1, 4);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 1, 1});
    Eigen::MatrixXf obs = Eigen::MatrixXf::Zero(1, 2), actions;
    CHECK_THROWS_WITH(algo.predict_masked(obs, Eigen::MatrixXf::Ones(3, 2), true, actions),
                      Catch::Contains("expected 4 x 2"));
    CHECK_THROWS_WITH(algo.predict_masked(obs, Eigen::MatrixXf::Zero(4, 2), true, actions),
                      Catch::Contains("observation 0") && Catch::Contains("allows no action"));
  }
  SECTION("evaluation names the env and the step") {
    VecEnv env = masked_envs(1, 4);
    MaskablePPO algo(small_config(), {env.observation_space(), env.action_space(), 1, 1});
    MaskedEnv eval_env(4, 3);
    CHECK_THROWS_WITH(evaluate_policy(algo, eval_env, 1, true, 1),
                      Catch::Contains("Masked-v0 at step 3 of the episodes") &&
                          Catch::Contains("allows no action"));
  }
}
