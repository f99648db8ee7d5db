#include <catch2/catch.hpp>

#include "fakes/constant_env.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/env/vec_env.hpp"

using namespace rlrun;

namespace {

struct Batch {
  Eigen::MatrixXf obs, actions;
  Eigen::RowVectorXf old_log_prob, old_values, advantages, returns;
};

double loss_of(ActorCriticPolicy& policy, const Batch& b, float clip, std::optional<float> clip_vf,
               float ent_coef, Eigen::RowVectorXf& gv, Eigen::RowVectorXf& gl,
               Eigen::RowVectorXf& ge) {
  Eigen::RowVectorXf v, lp, h;
  policy.evaluate_actions(b.obs, b.actions, v, lp, h);
  return ppo_loss({v, lp, h, b.old_log_prob, b.old_values, b.advantages, b.returns}, clip, clip_vf,
                  ent_coef, 0.5f, gv, gl, ge)
      .loss;
}

ActorCriticPolicyConfig small_policy() {
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{8, 8}, {8, 8}};
  return cfg;
}

// Finite-difference check of d(PPO loss)/d(every parameter) through the whole policy.
// With use_sde the Box head is gSDE's (log_std a latent x action matrix, or latent x 1;
// cfg.full_std says which).
void check_policy_gradient(const Space& obs_space, const Space& act_space,
                           const ActorCriticPolicyConfig& cfg = small_policy(), float clip = 0.2f,
                           std::optional<float> clip_vf = 0.1f, float ent_coef = 0.05f,
                           bool use_sde = false) {
  Rng rng(3);
  ActorCriticPolicy policy(obs_space, act_space, cfg, rng, use_sde);
  if (use_sde) policy.reset_noise(rng, 16);  // one matrix per sample: th.bmm
  const int n = 16, obs_dim = obs_space.flat_dim();
  Batch b;
  b.obs = Eigen::MatrixXf::Random(obs_dim, n);
  if (!obs_space.is_box())
    for (int j = 0; j < n; ++j) obs_space.sample(rng, {b.obs.col(j).data(), size_t(obs_dim)});
  Eigen::RowVectorXf v, lp, h;
  Eigen::MatrixXf acts;
  Eigen::RowVectorXf values, log_probs;
  policy.act(b.obs, rng, false, acts, values, log_probs);
  b.actions = acts;
  // Old log-probs and values offset from the current ones so that half the samples are
  // clipped and half are not, none of them near a clipping kink (finite differences would
  // straddle it): |log ratio| is 0.05 (inside clip 0.2) or 0.6 (outside); value offsets 0.02
  // (inside clip 0.1) or 0.5.
  const float policy_offsets[4] = {-0.6f, -0.05f, 0.05f, 0.6f};
  const float value_offsets[4] = {0.5f, -0.02f, 0.02f, -0.5f};
  b.old_log_prob = log_probs;
  b.old_values = values;
  for (int j = 0; j < n; ++j) {
    b.old_log_prob(j) += policy_offsets[j % 4];
    b.old_values(j) += value_offsets[(j / 4) % 4];
  }
  b.advantages = Eigen::RowVectorXf::Random(n);
  b.returns = Eigen::RowVectorXf::Random(n);
  Eigen::RowVectorXf gv(n), gl(n), ge(n);

  policy.zero_grad();
  loss_of(policy, b, clip, clip_vf, ent_coef, gv, gl, ge);
  policy.backward(gv, gl, ge);
  int checked = 0;
  // gSDE in PPO detaches the latent features in the variance (SB3: learn_features=False), so a
  // finite difference of an actor hidden-layer weight, which moves the latent, measures a path
  // autograd does not take: those are checked through the Gaussian head; the action_net, the
  // critic and the log_std matrix are checked here.
  const Mlp& actor = policy.actor();
  const int head = actor.num_layers() - 1;
  const Eigen::Index hidden_params =
      actor.num_params() -
      static_cast<Eigen::Index>(actor.layer_out(head)) * (actor.layer_in(head) + 1);
  bool actor_block = true;
  for (ParamBlock block : policy.param_blocks()) {
    const Eigen::Index first = actor_block && use_sde ? hidden_params : 0;
    actor_block = false;
    for (Eigen::Index i = first; i < block.size; i += 7) {
      const float saved = block.value[i];
      const float eps = 1e-3f;
      block.value[i] = saved + eps;
      const double up = loss_of(policy, b, clip, clip_vf, ent_coef, gv, gl, ge);
      block.value[i] = saved - eps;
      const double down = loss_of(policy, b, clip, clip_vf, ent_coef, gv, gl, ge);
      block.value[i] = saved;
      const double numeric = (up - down) / (2 * eps);
      const double analytic = block.grad[i];
      INFO("param " << i << " analytic " << analytic << " numeric " << numeric);
      CHECK(analytic == Approx(numeric).epsilon(0.03).margin(5e-4));
      ++checked;
    }
  }
  CHECK(checked > 20);
}

}  // namespace

TEST_CASE("PPO loss gradient through the policy matches finite differences (Discrete)",
          "[algos][ppo][gradcheck]") {
  check_policy_gradient(Space::box(-1.0f, 1.0f, {4}), Space::discrete(3));
}

TEST_CASE("PPO loss gradient through the policy matches finite differences (Box)",
          "[algos][ppo][gradcheck]") {
  check_policy_gradient(Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {2}));
}

TEST_CASE("PPO loss gradient matches finite differences with separate pi/vf sizes, ELU, torch init",
          "[algos][ppo][gradcheck]") {
  // net_arch {pi: [8], vf: [7, 6]}, nn.ELU, ortho_init false: the towers differ in depth and
  // width, and torch's default init gives non-zero biases.
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{8}, {7, 6}};
  cfg.activation_fn = Activation::kELU;
  cfg.ortho_init = false;
  check_policy_gradient(Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {2}), cfg);
  // A linear policy head (pi: []), LeakyReLU in the value tower.
  cfg.net_arch = {{}, {24}};
  cfg.activation_fn = Activation::kLeakyReLU;
  check_policy_gradient(Space::box(-1.0f, 1.0f, {6}), Space::discrete(3), cfg);
}

TEST_CASE("PPO loss gradient through the policy matches finite differences (Box, gSDE)",
          "[algos][ppo][gradcheck][gsde]") {
  const bool full_std = GENERATE(true, false);
  INFO("full_std " << full_std);
  ActorCriticPolicyConfig cfg = small_policy();
  cfg.full_std = full_std;
  cfg.log_std_init = -0.5;
  check_policy_gradient(Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {2}), cfg, 0.2f, 0.1f,
                        0.05f, true);
}

TEST_CASE("PPO loss gradient through the policy matches finite differences (MultiDiscrete)",
          "[algos][ppo][gradcheck]") {
  check_policy_gradient(Space::box(-1.0f, 1.0f, {3}), Space::multi_discrete({3, 2, 4}));
}

TEST_CASE("PPO loss gradient through the policy matches finite differences (MultiBinary)",
          "[algos][ppo][gradcheck]") {
  check_policy_gradient(Space::box(-1.0f, 1.0f, {3}), Space::multi_binary(4));
}

TEST_CASE("PPO loss gradient through the policy matches finite differences (Dict obs)",
          "[algos][ppo][gradcheck]") {
  check_policy_gradient(Space::dict({{"pos", Space::box(-1.0f, 1.0f, {2})},
                                     {"cell", Space::discrete(3)},
                                     {"bits", Space::multi_binary(2)}}),
                        Space::discrete(3));
}

TEST_CASE("the policy sees a Dict observation as SB3's CombinedExtractor output", "[algos][ppo]") {
  // Keys sorted: cell (Discrete 3 -> one-hot), grid (MultiDiscrete [2 2] -> two one-hots),
  // pos (Box 2). A policy on the Dict and one on the equivalent Box of 9 features start from
  // the same weights (same rng) and must give the same outputs.
  const Space dict = Space::dict({{"pos", Space::box(-1.0f, 1.0f, {2})},
                                  {"cell", Space::discrete(3)},
                                  {"grid", Space::multi_discrete({2, 2})}});
  const Space box = Space::box(-1.0f, 1.0f, {9});
  const ActorCriticPolicyConfig cfg;
  Rng rng_a(5), rng_b(5);
  ActorCriticPolicy on_dict(dict, Space::multi_binary(3), cfg, rng_a);
  ActorCriticPolicy on_box(box, Space::multi_binary(3), cfg, rng_b);
  CHECK(on_dict.encoder().features_dim() == 9);
  CHECK(on_dict.actor().in_dim() == 9);
  Eigen::MatrixXf raw(5, 2), encoded(9, 2);
  raw.col(0) << 2, 1, 0, 0.25f, -0.5f;
  encoded.col(0) << 0, 0, 1, 0, 1, 1, 0, 0.25f, -0.5f;
  raw.col(1) << 0, 0, 1, -1, 1;
  encoded.col(1) << 1, 0, 0, 1, 0, 0, 1, -1, 1;
  Eigen::MatrixXf a_dict, a_box;
  Eigen::RowVectorXf v_dict, v_box, lp_dict, lp_box;
  on_dict.act(raw, rng_a, true, a_dict, v_dict, lp_dict);
  on_box.act(encoded, rng_b, true, a_box, v_box, lp_box);
  CHECK(a_dict == a_box);
  CHECK(v_dict == v_box);
  CHECK(lp_dict == lp_box);
  // Same parameter names as SB3's MultiInputPolicy (its Flatten extractors have none).
  TensorMap tensors;
  on_dict.save(tensors);
  CHECK(tensors.count("mlp_extractor.policy_net.0.weight") == 1);
  CHECK(tensors.at("mlp_extractor.policy_net.0.weight").shape == std::vector<int64_t>{64, 9});
  CHECK(tensors.size() == 12);
}

TEST_CASE("the policy's action_net has SB3's size for each action space", "[algos][ppo]") {
  Rng rng(1);
  const ActorCriticPolicyConfig cfg;
  const Space obs = Space::box(-1.0f, 1.0f, {2});
  const auto check = [&](const Space& act, int outputs, int action_dim, bool log_std) {
    ActorCriticPolicy policy(obs, act, cfg, rng);
    INFO(act.describe());
    CHECK(policy.actor().out_dim() == outputs);
    CHECK(policy.action_dim() == action_dim);
    TensorMap tensors;
    policy.save(tensors);
    CHECK(tensors.at("action_net.weight").shape == std::vector<int64_t>{outputs, 64});
    CHECK(tensors.count("log_std") == (log_std ? 1u : 0u));
  };
  check(Space::discrete(5), 5, 1, false);
  check(Space::multi_discrete({3, 2, 4}), 9, 3, false);
  check(Space::multi_binary(6), 6, 6, false);
  check(Space::box(-1.0f, 1.0f, {2}), 2, 2, true);
  CHECK_THROWS_AS(ActorCriticPolicy(obs, Space::dict({{"a", Space::discrete(2)}}), cfg, rng),
                  std::invalid_argument);
}

TEST_CASE("PPO loss terms on a hand-made batch", "[algos][ppo]") {
  Eigen::RowVectorXf v(2), lp(2), h(2), olp(2), ov(2), adv(2), ret(2), gv(2), gl(2), ge(2);
  v << 1, 2;
  lp << std::log(1.5f), std::log(0.5f);  // ratios 1.5 and 0.5 against old log-prob 0
  h << 0.5, 0.7;
  olp << 0, 0;
  ov << 1, 2;
  adv << 1, -1;
  ret << 2, 2;
  const PpoLossTerms t =
      ppo_loss({v, lp, h, olp, ov, adv, ret}, 0.2f, std::nullopt, 0.1f, 0.5f, gv, gl, ge);
  // Sample 0: A=1, r=1.5 -> min(1.5, 1.2) = 1.2 (clipped: no gradient).
  // Sample 1: A=-1, r=0.5 -> min(-0.5, -0.8) = -0.8 (clipped: no gradient).
  CHECK(t.policy_loss == Approx(-(1.2 - 0.8) / 2));
  CHECK(gl(0) == 0.0f);
  CHECK(gl(1) == 0.0f);
  CHECK(t.clip_fraction == Approx(1.0));
  CHECK(t.value_loss == Approx((1.0 + 0.0) / 2));
  CHECK(gv(0) == Approx(0.5 * 2 * (1 - 2) / 2));
  CHECK(t.entropy_loss == Approx(-0.6));
  CHECK(t.loss == Approx(t.policy_loss + 0.1 * t.entropy_loss + 0.5 * t.value_loss));
}

TEST_CASE("advantage normalisation uses the unbiased std like torch", "[algos][ppo]") {
  Eigen::RowVectorXf a(3);
  a << 1, 2, 3;
  normalize_advantages(a);
  CHECK(a(0) == Approx(-1.0).epsilon(1e-5));
  CHECK(a(2) == Approx(1.0).epsilon(1e-5));
}

namespace {
// Runs one rollout of PPO on ConstantEnv copies and returns (reward, value) pairs.
void check_timeout_bootstrap(bool truncate) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < 2; ++i) envs.push_back(std::make_unique<fakes::ConstantEnv>(truncate, 3));
  VecEnv env(std::move(envs));
  PPO::Config cfg;
  cfg.n_steps = 6;
  cfg.batch_size = 4;
  cfg.n_epochs = 1;
  cfg.gamma = 0.9;
  PPO ppo(cfg, AlgorithmSetup{env.observation_space(), env.action_space(), 2, 1});
  TrainingHooks hooks;
  ppo.learn(env, 12, hooks);
  const auto& rewards = ppo.rollout_rewards();
  const auto& values = ppo.rollout_values();
  for (int t = 0; t < 6; ++t) {
    for (int e = 0; e < 2; ++e) {
      const bool episode_end = (t + 1) % 3 == 0;
      // final_obs == obs for this env, so V(final_obs) is the value stored for that step.
      const float expected = episode_end && truncate ? 1.0f + 0.9f * values(t, e) : 1.0f;
      CHECK(rewards(t, e) == Approx(expected));
    }
  }
}
}  // namespace

TEST_CASE("PPO bootstraps truncated steps from V(final_obs), never terminated ones",
          "[algos][ppo]") {
  check_timeout_bootstrap(true);
  check_timeout_bootstrap(false);
}

TEST_CASE("PPO is deterministic for a seed", "[algos][ppo]") {
  auto run = [] {
    std::vector<EnvPtr> envs;
    for (int i = 0; i < 2; ++i) envs.push_back(std::make_unique<fakes::ConstantEnv>(true, 5));
    VecEnv env(std::move(envs));
    PPO::Config cfg;
    cfg.n_steps = 16;
    cfg.batch_size = 8;
    PPO ppo(cfg, AlgorithmSetup{env.observation_space(), env.action_space(), 2, 42});
    TrainingHooks hooks;
    ppo.learn(env, 64, hooks);
    TensorMap t;
    ppo.save(t);
    return t.at("action_net.weight").bytes;
  };
  CHECK(run() == run());
}
