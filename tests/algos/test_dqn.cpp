// DQN (src/rlrun/algos/dqn/): the TD target, Huber loss and gradient through linear networks
// on hand-made numbers, a finite-difference check of the loss gradient through the Q-network
// (against a double re-implementation), gradient clipping, the epsilon schedule, the
// target-update period with several envs, timeout bootstrapping, model tensors, and short runs
// through the registry. The learning bars are hidden ([.slow]); the update micro-benchmark too
// ([.bench]).
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "algos/discrete_replay_batch.hpp"
#include "fakes/constant_env.hpp"
#include "nn/grad_check.hpp"
#include "nn/nature_cnn_gradient_check.hpp"
#include "nn/nature_cnn_reference.hpp"
#include "rlrun/algos/common/exploration_schedule.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;
using test::numeric_gradient;
using test::require_grad_close;

namespace {

AlgorithmSetup discrete_setup(int obs_dim, int n_actions, int n_envs = 1, uint64_t seed = 0) {
  return AlgorithmSetup{Space::box(-1.0f, 1.0f, {obs_dim}), Space::discrete(n_actions), n_envs,
                        seed};
}

// One sample through test::mlp_forward.
Eigen::VectorXd mlp_forward(const Mlp& net, const Eigen::VectorXd& p, const Eigen::VectorXd& x) {
  return test::mlp_forward(net, p, x).col(0);
}

VecEnv constant_vec_env(int n_envs, bool truncate, int episode_length) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n_envs; ++i)
    envs.push_back(std::make_unique<fakes::ConstantEnv>(truncate, episode_length));
  return VecEnv(std::move(envs));
}

}  // namespace

// ---- (1) target and loss on hand-made numbers ---------------------------------------------

TEST_CASE("DQN loss and gradient through linear Q-networks with set weights", "[algos][dqn]") {
  DQN::Config cfg;
  cfg.off_policy.gamma = 0.5;
  cfg.policy.net_arch = {};  // Q(s) = W s + b, so every number below follows by hand
  cfg.max_grad_norm = 1e9;   // no clipping
  DQN dqn(cfg, discrete_setup(2, 2));
  dqn.q_net().weight(0) << 1, 0,  //
      0, 2;
  dqn.q_net().bias(0) << 0, 1;             // Q(s) = (s0, 2 s1 + 1)
  dqn.q_net_target().weight(0) << 0.5, 0,  //
      0, 0.5;
  dqn.q_net_target().bias(0) << 0, 0;  // Q'(s') = s' / 2

  ReplayBatch b;
  b.obs.resize(2, 2);
  b.obs << 1, 3,  //
      0.25, 1;
  b.next_obs.resize(2, 2);
  b.next_obs << 2, 4,  //
      4, 0;
  b.actions.resize(1, 2);
  b.actions << 1, 0;
  b.rewards.resize(2);
  b.rewards << 1, -1;
  b.dones.resize(2);
  b.dones << 0, 1;
  // Learning rate 0: the step leaves the weights as set and the gradient in grads().
  const double loss = dqn.train_on_batch(b, 0.0f);
  // Sample 0: target 1 + 0.5 max(1, 2) = 2; Q(s, 1) = 1.5; diff -0.5 -> loss 0.125, dq -0.5.
  // Sample 1: terminal, target -1; Q(s, 0) = 3; diff 4 -> loss 3.5, dq 1 (clamped).
  CHECK(dqn.td_targets()(0) == Approx(2));
  CHECK(dqn.td_targets()(1) == Approx(-1));
  CHECK(loss == Approx((0.125 + 3.5) / 2));
  // Mean over the batch: dq/2 per sample; dW(a, :) = dq s^T, db(a) = dq.
  Eigen::MatrixXf dw(2, 2);
  dw << 0.5f * 3, 0.5f * 1,  //
      -0.25f * 1, -0.25f * 0.25f;
  CHECK(dqn.q_net().weight_grad(0).isApprox(dw));
  CHECK(dqn.q_net().bias_grad(0)(0) == Approx(0.5));
  CHECK(dqn.q_net().bias_grad(0)(1) == Approx(-0.25));
  // The target network gets no gradient.
  CHECK(dqn.q_net_target().grads().isZero());
}

// ---- (2) finite differences -----------------------------------------------------------------

TEST_CASE("DQN loss gradient w.r.t. every q_net parameter matches finite differences",
          "[algos][dqn][gradcheck]") {
  // 20 samples run on one core, 41 on two (nn/batch_split.hpp).
  const int n = GENERATE(20, 41);
  INFO("batch " << n);
  DQN::Config cfg;
  // Layers wider than a SIMD packet and batches that are not a multiple of the kernels' 6-column
  // tile, so that the vectorised paths of the 256-wide zoo networks are the ones checked.
  cfg.policy.net_arch = {40, 24};
  cfg.off_policy.gamma = 0.9;
  cfg.max_grad_norm = 1e9;
  const int obs_dim = 3, n_actions = 3;
  DQN dqn(cfg, discrete_setup(obs_dim, n_actions, 1, 5));
  // A target network unlike the online one, and targets spread so that some TD errors fall in
  // the quadratic and some in the linear part of the Huber loss.
  Rng rng(7);
  for (Eigen::Index i = 0; i < dqn.q_net_target().num_params(); ++i)
    dqn.q_net_target().params()(i) += static_cast<float>(rng.uniform(-0.5, 0.5));
  const ReplayBatch b = test::random_discrete_batch(rng, obs_dim, n_actions, n);
  const double loss = dqn.train_on_batch(b, 0.0f);
  const Eigen::VectorXd analytic = dqn.q_net().grads().cast<double>();

  // Targets re-derived in double from the target network's parameters.
  const Eigen::VectorXd target_params = dqn.q_net_target().params().cast<double>();
  Eigen::VectorXd targets(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd next_q =
        mlp_forward(dqn.q_net_target(), target_params, b.next_obs.col(j).cast<double>());
    targets(j) = b.rewards(j) + (1.0 - b.dones(j)) * 0.9 * next_q.maxCoeff();
    CHECK(dqn.td_targets()(j) == Approx(targets(j)).epsilon(1e-5).margin(1e-5));
  }
  int quadratic = 0, linear = 0;
  const auto double_loss = [&](const Eigen::VectorXd& p) {
    double sum = 0.0;
    quadratic = linear = 0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd q = mlp_forward(dqn.q_net(), p, b.obs.col(j).cast<double>());
      const double d = q(static_cast<int>(b.actions(0, j))) - targets(j);
      if (std::abs(d) < 1.0) {
        sum += 0.5 * d * d;
        ++quadratic;
      } else {
        sum += std::abs(d) - 0.5;
        ++linear;
      }
    }
    return sum / n;
  };
  const Eigen::VectorXd p0 = dqn.q_net().params().cast<double>();
  CHECK(double_loss(p0) == Approx(loss).epsilon(1e-5));
  CHECK(quadratic > 0);
  CHECK(linear > 0);
  require_grad_close(analytic, numeric_gradient(double_loss, p0));
}

TEST_CASE("DQN CnnPolicy: the loss gradient reaches q_net's NatureCNN, as central differences say",
          "[algos][dqn][cnn][gradcheck]") {
  // SB3's CnnPolicy for DQN: q_net = NatureCNN features -> Linear(features_dim, n_actions)
  // (net_arch []), the target network with a NatureCNN of its own. A 36x36 gray image, the
  // smallest NatureCNN takes, channels last as Gymnasium's images.
  DQN::Config cfg;
  cfg.policy.features_extractor_class = FeaturesExtractor::kNatureCnn;
  cfg.policy.features_dim = 8;
  cfg.policy.net_arch = {};
  cfg.off_policy.gamma = 0.9;
  cfg.max_grad_norm = 1e9;
  const int n_actions = 3, n = 6;
  const AlgorithmSetup setup{Space::image({36, 36, 1}), Space::discrete(n_actions), 1, 11};
  DQN dqn(cfg, setup);
  REQUIRE(dqn.cnn() != nullptr);
  Rng rng(13);
  ReplayBatch b = test::random_discrete_batch(rng, 36 * 36, n_actions, n);
  for (Eigen::Index k = 0; k < b.obs.size(); ++k) {
    b.obs.data()[k] = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
    b.next_obs.data()[k] = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
  }
  const double loss = dqn.train_on_batch(b, 0.0f);
  const NatureCnn cnn = *dqn.cnn();
  const Eigen::VectorXd head = dqn.q_net().params().cast<double>();
  // The Huber loss of the online network in double, its features from the reference CNN
  // (torch's tensors), the targets as DQN computed them from the target network.
  auto double_loss = [&](const NatureCnn& net) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd q =
          mlp_forward(dqn.q_net(), head, test::reference_features(net, b.obs.col(j)));
      const double d = q(static_cast<int>(b.actions(0, j))) - dqn.td_targets()(j);
      sum += std::abs(d) < 1.0 ? 0.5 * d * d : std::abs(d) - 0.5;
    }
    return sum / n;
  };
  CHECK(double_loss(cnn) == Approx(loss).epsilon(1e-4));
  CHECK(test::check_cnn_gradient(cnn, double_loss, "CNN", 61, 1e-5, 1e-2) > 60);
  CHECK(cnn.grads().norm() > 0.0f);

  // SB3's state_dict names: each network's extractor under its own module.
  TensorMap tensors;
  dqn.save(tensors);
  CHECK(tensors.at("q_net.features_extractor.cnn.0.weight").shape ==
        std::vector<int64_t>{32, 1, 8, 8});
  CHECK(tensors.count("q_net_target.features_extractor.linear.0.weight") == 1);
  CHECK(tensors.at("q_net.0.weight").shape == std::vector<int64_t>{n_actions, 8});
  DQN loaded(cfg, setup);
  loaded.load(tensors);
  CHECK(loaded.cnn()->params() == dqn.cnn()->params());
  // A vector observation is refused with SB3's reason.
  CHECK_THROWS_WITH(DQN(cfg, discrete_setup(4, 2)),
                    Catch::Contains("you should use NatureCNN only with images"));
}

TEST_CASE(
    "DQN loss gradient at rl-zoo sizes (6-256-256-3, batch 128) matches finite "
    "differences on sampled parameters",
    "[algos][dqn][gradcheck]") {
  // The production kernel paths for 256-wide layers and a 128-column batch; every layer's
  // weights and biases are sampled (a full check would take minutes in double).
  DQN::Config cfg;
  cfg.policy.net_arch = {256, 256};
  cfg.max_grad_norm = 1e9;
  const int obs_dim = 6, n_actions = 3, n = 128;
  DQN dqn(cfg, discrete_setup(obs_dim, n_actions, 1, 17));
  Rng rng(5);
  for (Eigen::Index i = 0; i < dqn.q_net_target().num_params(); ++i)
    dqn.q_net_target().params()(i) += static_cast<float>(rng.uniform(-0.05, 0.05));
  const ReplayBatch b = test::random_discrete_batch(rng, obs_dim, n_actions, n);
  dqn.train_on_batch(b, 0.0f);
  const Eigen::VectorXd analytic = dqn.q_net().grads().cast<double>();
  const Eigen::VectorXd targets = dqn.td_targets().transpose().cast<double>();
  const Mlp& net = dqn.q_net();
  const auto double_loss = [&](const Eigen::VectorXd& p) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd q = mlp_forward(net, p, b.obs.col(j).cast<double>());
      const double d = q(static_cast<int>(b.actions(0, j))) - targets(j);
      sum += std::abs(d) < 1.0 ? 0.5 * d * d : std::abs(d) - 0.5;
    }
    return sum / n;
  };
  Eigen::VectorXd p = net.params().cast<double>();
  std::vector<Eigen::Index> picked;
  Eigen::Index offset = 0;
  for (int l = 0; l < net.num_layers(); ++l) {
    const Eigen::Index w = static_cast<Eigen::Index>(net.layer_in(l)) * net.layer_out(l);
    for (int i = 0; i < 8; ++i) picked.push_back(offset + static_cast<Eigen::Index>(rng.below(w)));
    for (int i = 0; i < 4; ++i)
      picked.push_back(offset + w + static_cast<Eigen::Index>(rng.below(net.layer_out(l))));
    offset += w + net.layer_out(l);
  }
  Eigen::VectorXd a(picked.size()), numeric(picked.size());
  for (std::size_t i = 0; i < picked.size(); ++i) {
    const Eigen::Index k = picked[i];
    const double saved = p(k), h = 1e-6;
    p(k) = saved + h;
    const double up = double_loss(p);
    p(k) = saved - h;
    const double down = double_loss(p);
    p(k) = saved;
    numeric(i) = (up - down) / (2 * h);
    a(i) = analytic(k);
  }
  require_grad_close(a, numeric, 2e-3);
}

TEST_CASE("DQN clips the gradient to max_grad_norm before its Adam step", "[algos][dqn]") {
  DQN::Config cfg;
  cfg.policy.net_arch = {64, 48};
  cfg.max_grad_norm = 0.1;  // below the gradient norms of these batches
  DQN clipped(cfg, discrete_setup(5, 4, 1, 9));
  cfg.max_grad_norm = 1e9;
  DQN unclipped(cfg, discrete_setup(5, 4, 1, 9));
  Rng rng(21);
  const ReplayBatch b = test::random_discrete_batch(rng, 5, 4, 37);  // odd: unequal halves
  clipped.train_on_batch(b, 0.0f);
  unclipped.train_on_batch(b, 0.0f);
  const float norm = unclipped.q_net().grads().norm();
  CHECK(clipped.last_grad_norm() == Approx(norm).epsilon(1e-5));
  CHECK(norm > 0.1f);
  CHECK(clipped.q_net().grads().norm() == Approx(0.1).epsilon(1e-4));
  CHECK(clipped.q_net().grads().isApprox(unclipped.q_net().grads() * (0.1f / (norm + 1e-6f))));
  // And the step moves the weights.
  const Eigen::VectorXf before = clipped.q_net().params();
  clipped.train_on_batch(b, 1e-3f);
  CHECK(clipped.q_net().params() != before);
}

// ---- (3) exploration schedule ---------------------------------------------------------------

TEST_CASE("DQN epsilon follows SB3's get_linear_fn", "[algos][dqn]") {
  const LinearDecay eps{1.0, 0.05, 0.1};
  CHECK(eps(1.0) == Approx(1.0));
  CHECK(eps(0.95) == Approx(1.0 - 0.5 * 0.95));  // halfway through the decay
  CHECK(eps(0.975) == Approx(1.0 - 0.25 * 0.95));
  CHECK(eps(0.9) == Approx(0.05));  // progress == fraction: end of the linear part
  CHECK(eps(0.5) == 0.05);
  CHECK(eps(0.0) == 0.05);
  const LinearDecay slow{0.5, 0.1, 2.0};  // fraction > 1: still decaying at the end
  CHECK(slow(0.0) == Approx(0.5 - 0.4 * 0.5));
}

TEST_CASE("DQN sets epsilon after every env step from the progress so far", "[algos][dqn]") {
  VecEnv env = constant_vec_env(2, true, 7);
  DQN::Config cfg;
  cfg.exploration_fraction = 0.5;
  cfg.exploration_initial_eps = 0.8;
  cfg.exploration_final_eps = 0.2;
  cfg.off_policy.learning_starts = 1000;  // no training needed here
  cfg.policy.net_arch = {4};
  DQN dqn(cfg, discrete_setup(1, 2, 2));
  std::vector<double> seen;
  TrainingHooks hooks;
  hooks.on_step = [&](int64_t) {
    seen.push_back(dqn.exploration_rate());
    return true;
  };
  CHECK(dqn.exploration_rate() == 0.0);  // SB3's initial value, before the first _on_step
  dqn.learn(env, 40, hooks);
  REQUIRE(seen.size() == 20);
  // The hook of step k runs before that step's _on_step: epsilon is from progress (k-1) * 2 / 40.
  const LinearDecay schedule{0.8, 0.2, 0.5};
  for (int k = 2; k <= 20; ++k) CHECK(seen[k - 1] == Approx(schedule(1.0 - (k - 1) * 2.0 / 40.0)));
  CHECK(seen[5] == Approx(0.8 - 0.6 * (10.0 / 40.0) / 0.5));
  CHECK(dqn.exploration_rate() == Approx(0.2));
}

// ---- (4) target network period --------------------------------------------------------------

namespace {
// Trains with an update after every VecEnv step and returns the calls (1-based) after which
// the target network changed, checking that each change copies the online network as it was
// at that call.
std::vector<int> target_update_calls(int n_envs, int64_t interval, int calls) {
  VecEnv env = constant_vec_env(n_envs, true, 5);
  DQN::Config cfg;
  cfg.target_update_interval = interval;
  cfg.off_policy.learning_starts = 0;
  cfg.off_policy.train_freq = TrainFreq{1, false};
  cfg.off_policy.gradient_steps = 1;
  cfg.off_policy.batch_size = 4;
  cfg.learning_rate = Schedule::constant(1e-2);
  cfg.policy.net_arch = {4};
  DQN dqn(cfg, discrete_setup(1, 2, n_envs, 3));
  dqn.q_net_target().params().array() += 1.0f;  // so that even a copy before any update shows
  // Snapshots at each hook, i.e. after env step k and before that step's _on_step (the
  // update of step k then runs after _on_step).
  std::vector<Eigen::VectorXf> target, online;
  TrainingHooks hooks;
  hooks.on_step = [&](int64_t) {
    target.push_back(dqn.q_net_target().params());
    online.push_back(dqn.q_net().params());
    return true;
  };
  dqn.learn(env, static_cast<int64_t>(calls) * n_envs, hooks);
  target.push_back(dqn.q_net_target().params());
  CHECK(dqn.n_calls() == calls);
  CHECK(dqn.n_updates() == calls);
  std::vector<int> changed;
  for (int k = 1; k <= calls; ++k) {
    if (target[k] == target[k - 1]) continue;
    changed.push_back(k);
    CHECK(target[k] == online[k - 1]);  // tau = 1: a hard copy of q_net at call k
  }
  return changed;
}
}  // namespace

TEST_CASE("DQN copies the target every target_update_interval / n_envs VecEnv steps",
          "[algos][dqn]") {
  CHECK(target_update_calls(2, 10, 20) == std::vector<int>{5, 10, 15, 20});
  CHECK(target_update_calls(1, 4, 10) == std::vector<int>{4, 8});
  // Fewer steps in the interval than envs: every VecEnv step (SB3 warns about this).
  CHECK(target_update_calls(4, 3, 5) == std::vector<int>{1, 2, 3, 4, 5});
}

TEST_CASE("DQN soft target update with tau < 1", "[algos][dqn]") {
  VecEnv env = constant_vec_env(1, true, 5);
  DQN::Config cfg;
  cfg.target_update_interval = 1;
  cfg.off_policy.tau = 0.25;
  cfg.off_policy.learning_starts = 100;  // no training: q_net stays put
  cfg.off_policy.train_freq = TrainFreq{1, false};
  cfg.policy.net_arch = {4};
  DQN dqn(cfg, discrete_setup(1, 2));
  const Eigen::VectorXf q = dqn.q_net().params();
  dqn.q_net_target().params().setZero();
  TrainingHooks hooks;
  dqn.learn(env, 2, hooks);
  // Two updates: target = q (1 - 0.75^2).
  CHECK(dqn.q_net_target().params().isApprox(q * (1.0f - 0.75f * 0.75f)));
}

// ---- (5) timeouts -------------------------------------------------------------------------

namespace {
void check_timeout_targets(bool truncate) {
  VecEnv env = constant_vec_env(2, truncate, 3);
  DQN::Config cfg;
  cfg.off_policy.gamma = 0.9;
  cfg.off_policy.learning_starts = 1000;  // collect only: the networks stay as initialised
  cfg.off_policy.train_freq = TrainFreq{1, false};
  cfg.policy.net_arch = {4};
  DQN dqn(cfg, discrete_setup(1, 2, 2, 11));
  TrainingHooks hooks;
  dqn.learn(env, 18, hooks);  // 3 episodes per env, every third transition ends one
  REQUIRE(dqn.replay_buffer().size() == 18);
  Rng rng(1);
  ReplayBatch batch;
  dqn.replay_buffer().sample(200, rng, batch);
  dqn.train_on_batch(batch, 0.0f);
  // Every next observation is the constant 0.5, so the bootstrapped target is one number.
  const Eigen::VectorXf next_q = dqn.q_net_target().forward(Eigen::MatrixXf::Constant(1, 1, 0.5f));
  const float bootstrapped = 1.0f + 0.9f * next_q.maxCoeff();
  int terminal = 0;
  for (int j = 0; j < 200; ++j) {
    if (batch.dones(j) == 1.0f) {
      ++terminal;
      CHECK(dqn.td_targets()(j) == Approx(1.0));
    } else {
      CHECK(dqn.td_targets()(j) == Approx(bootstrapped));
    }
  }
  if (truncate) {
    CHECK(terminal == 0);  // time-limit ends bootstrap from the final observation
  } else {
    CHECK(terminal > 30);  // about a third of the samples end an episode
    CHECK(terminal < 100);
  }
}
}  // namespace

TEST_CASE("DQN bootstraps truncated transitions and never terminated ones", "[algos][dqn]") {
  check_timeout_targets(true);
  check_timeout_targets(false);
}

// ---- acting, model tensors, settings ------------------------------------------------------

TEST_CASE("DQN predict: greedy when deterministic, epsilon-greedy otherwise", "[algos][dqn]") {
  DQN::Config cfg;
  cfg.policy.net_arch = {};
  DQN dqn(cfg, discrete_setup(2, 3));
  dqn.q_net().weight(0) << 1, 0,  //
      0, 1,                       //
      -1, -1;
  dqn.q_net().bias(0).setZero();
  Eigen::MatrixXf obs(2, 3);
  obs << 1, 0, -1,  //
      0, 1, -1;
  Eigen::MatrixXf actions;
  dqn.predict(obs, true, actions);
  CHECK(actions == (Eigen::MatrixXf(1, 3) << 0, 1, 2).finished());
  // exploration_rate is 0 before training: stochastic predict is greedy too.
  dqn.predict(obs, false, actions);
  CHECK(actions == (Eigen::MatrixXf(1, 3) << 0, 1, 2).finished());
}

TEST_CASE("DQN saves SB3-named q_net and q_net_target tensors and loads them back",
          "[algos][dqn]") {
  DQN::Config cfg;
  cfg.policy.net_arch = {16, 8};
  DQN a(cfg, discrete_setup(4, 2, 1, 1));
  TensorMap t;
  a.save(t);
  for (const char* name :
       {"q_net.0.weight", "q_net.0.bias", "q_net.2.weight", "q_net.4.weight", "q_net.4.bias",
        "q_net_target.0.weight", "q_net_target.4.bias", "exploration_rate"})
    CHECK(t.count(name) == 1);
  CHECK(t.at("q_net.0.weight").shape == std::vector<int64_t>{16, 4});
  CHECK(t.at("q_net.4.weight").shape == std::vector<int64_t>{2, 8});
  // Fresh networks start as copies (DQNPolicy._build loads q_net's state_dict into the target).
  CHECK(t.at("q_net.2.weight").bytes == t.at("q_net_target.2.weight").bytes);

  DQN b(cfg, discrete_setup(4, 2, 1, 2));
  CHECK(b.q_net().params() != a.q_net().params());
  b.load(t);
  CHECK(b.q_net().params() == a.q_net().params());
  Eigen::MatrixXf obs = Eigen::MatrixXf::Random(4, 5), pa, pb;
  a.predict(obs, true, pa);
  b.predict(obs, true, pb);
  CHECK(pa == pb);
  t.erase("q_net_target.2.bias");
  CHECK_THROWS(b.load(t));
}

TEST_CASE("DQN rejects unsupported spaces and bad settings with a message", "[algos][dqn]") {
  const DQN::Config ok;
  CHECK_THROWS_AS(
      DQN(ok, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::box(-1.0f, 1.0f, {1}), 1, 0}),
      std::invalid_argument);
  {
    // Discrete observations reach the Q-network one-hot (SB3 preprocess_obs): 5 inputs.
    DQN discrete_obs(ok, AlgorithmSetup{Space::discrete(5), Space::discrete(2), 1, 0});
    TensorMap tensors;
    discrete_obs.save(tensors);
    CHECK(tensors.at("q_net.0.weight").shape == std::vector<int64_t>{64, 5});
    Eigen::MatrixXf obs(1, 2), actions;
    obs << 4.0f, 0.0f;
    discrete_obs.predict(obs, true, actions);
    CHECK(actions.cols() == 2);
  }
  const auto rejects = [](auto change) {
    DQN::Config c;
    change(c);
    CHECK_THROWS_AS(DQN(c, discrete_setup(3, 2)), std::invalid_argument);
  };
  rejects([](DQN::Config& c) { c.target_update_interval = 0; });
  rejects([](DQN::Config& c) { c.exploration_fraction = 0.0; });
  rejects([](DQN::Config& c) { c.exploration_final_eps = 1.5; });
  rejects([](DQN::Config& c) { c.max_grad_norm = 0.0; });
  rejects([](DQN::Config& c) { c.off_policy.tau = 0.0; });
  rejects([](DQN::Config& c) { c.off_policy.batch_size = 0; });
  try {
    DQN(ok, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::box(-1.0f, 1.0f, {1}), 1, 0});
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("Discrete") != std::string::npos);
  }
}

// ---- (6) through the registry -------------------------------------------------------------

namespace {
Experiment cartpole_experiment(const std::string& out_dir, int64_t steps, uint64_t seed) {
  const std::string yaml = "run: {name: dqn_smoke, seed: " + std::to_string(seed) +
                           ", total_timesteps: " + std::to_string(steps) + ", out_dir: " + out_dir +
                           ", console_interval: 1000}\n"
                           "env: {id: CartPole-v1, n_envs: 2}\n"
                           "algo: {id: DQN, learning_starts: 100, batch_size: 16, "
                           "train_freq: 8, gradient_steps: 2, target_update_interval: 50, "
                           "learning_rate: lin_1e-3, policy: {net_arch: [16, 16]}}\n";
  return parse_experiment(ConfigNode::load_string(yaml, "dqn.yaml"), builtin_registry());
}
}  // namespace

TEST_CASE(
    "DQN trains a few hundred steps on CartPole-v1 through the registry, "
    "deterministically",
    "[algos][dqn]") {
  testing::TempDir dir("dqn_smoke");
  const auto run = [&](uint64_t seed) {
    const TrainOutcome outcome = train_experiment(cartpole_experiment(dir.str(), 600, seed),
                                                  builtin_registry(), testing::test_execution());
    CHECK(outcome.timesteps == 608);  // whole train_freq rounds of 8 steps x 2 envs, as SB3
    return read_model(outcome.model_path);
  };
  const ModelFile m1 = run(3);
  const ModelFile m2 = run(3);
  CHECK(m1.meta.algorithm == "DQN");
  CHECK(m1.tensors.at("q_net.4.weight").bytes == m2.tensors.at("q_net.4.weight").bytes);
  CHECK(m1.tensors.at("q_net.4.weight").bytes != m1.tensors.at("q_net_target.4.weight").bytes);
  // 608 steps with the schedule reaching its end at 10% of training.
  CHECK(*m1.tensors.at("exploration_rate").data<double>() == Approx(0.05));

  const Experiment stored = experiment_from_model(m1, builtin_registry());
  EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
  auto loaded = algorithm_from_model(m1, stored, builtin_registry(), env->observation_space(),
                                     env->action_space());
  const EvalResult r = evaluate_policy(*loaded, *env, 2, true, 5);
  CHECK(r.returns.size() == 2);
}

// ---- hidden: speed and learning bars ------------------------------------------------------

TEST_CASE("DQN update micro-benchmark (rl-zoo CartPole sizes)", "[.bench][dqn_bench]") {
  // anchors.md counting: 2 in out FLOP per layer and sample forward, twice that backward; a
  // gradient step is target forward + online forward + backward = 4 forwards.
  DQN::Config cfg;
  cfg.policy.net_arch = {256, 256};
  cfg.off_policy.batch_size = 64;
  AlgorithmSetup setup = discrete_setup(4, 2, 1, 1);
  setup.pool = &testing::test_thread_pool();
  DQN dqn(cfg, setup);
  Rng rng(1);
  const ReplayBatch b = test::random_discrete_batch(rng, 4, 2, 64);
  for (int i = 0; i < 200; ++i) dqn.train_on_batch(b, 1e-6f);
  const int iters = 2000;
  double best = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) dqn.train_on_batch(b, 1e-6f);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / iters);
  }
  const Mlp& q = dqn.q_net();
  double fwd = 0.0;
  for (int l = 0; l < q.num_layers(); ++l) fwd += 2.0 * q.layer_in(l) * q.layer_out(l) * 64;
  const double flops = 4.0 * fwd;
  std::printf(
      "DQN gradient step (4-256-256-2, batch 64, %d threads): %.1f us, %.1f MFLOP, "
      "%.1f GFLOP/s; 24.5k steps: %.1f s\n",
      testing::test_thread_pool().threads(), best * 1e6, flops * 1e-6, flops / best * 1e-9,
      best * 24.5e3);
  CHECK(q.params().allFinite());
}

namespace {
double train_and_evaluate(const std::string& config, uint64_t seed) {
  testing::TempDir dir("dqn_slow_" + std::to_string(seed));
  Registry registry = make_builtin_registry();
  Experiment e =
      load_experiment(std::string(RLRUN_SOURCE_DIR) + "/configs/" + config,
                      {"run.out_dir=" + dir.str(), "run.seed=" + std::to_string(seed)}, registry);
  const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
  // A config that evaluates during training is scored by the best model it kept (the zoo's
  // --load-best; configs/cartpole_dqn.yaml).
  std::string path = outcome.model_path;
  const std::string best = outcome.run_dir + "/best_model.zip";
  if (std::ifstream(best).good()) path = best;
  const ModelFile model = read_model(path);
  const Experiment stored = experiment_from_model(model, builtin_registry());
  EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
  auto loaded = algorithm_from_model(model, stored, builtin_registry(), env->observation_space(),
                                     env->action_space());
  // As scripts/bench.sh measures: `rlrun eval --model model.zip --episodes 10` (deterministic,
  // first reset seeded 0).
  const double mean = evaluate_policy(*loaded, *env, 10, true, 0).mean_return();
  std::printf("%s seed %llu: %.1f s, eval %.1f\n", config.c_str(),
              static_cast<unsigned long long>(seed), outcome.wall_seconds, mean);
  return mean;
}
}  // namespace

TEST_CASE("DQN learns CartPole-v1 (rl-zoo settings, 5e4 steps) in 2 of 3 seeds",
          "[.slow][algos][dqn_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) passed += train_and_evaluate("cartpole_dqn.yaml", seed) >= 475.0;
  CHECK(passed >= 2);
}

TEST_CASE("DQN learns MountainCar-v0 (rl-zoo settings, 1.2e5 steps) in 2 of 3 seeds",
          "[.slow][algos][dqn_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3})
    passed += train_and_evaluate("mountaincar_dqn.yaml", seed) >= -110.0;
  CHECK(passed >= 2);
}

TEST_CASE("DQN learns Acrobot-v1 (rl-zoo settings, 1e5 steps) in 2 of 3 seeds",
          "[.slow][algos][dqn_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) passed += train_and_evaluate("acrobot_dqn.yaml", seed) >= -100.0;
  CHECK(passed >= 2);
}
