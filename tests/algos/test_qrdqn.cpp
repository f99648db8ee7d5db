// QR-DQN (src/rlrun/algos/qrdqn/): the target quantiles, the quantile Huber loss (summed over the
// current quantiles, averaged over the batch and the targets) and its gradient through a linear
// network on hand-made numbers, a finite-difference check through a hidden-layer network
// against a double re-implementation of sb3-contrib's train(), the greedy action from the mean
// of each action's quantiles, Adam's eps = 0.01 / batch_size, no clipping by default, model
// tensors under sb3-contrib's names, and a short run through the registry. The learning bar is
// hidden ([.slow]).
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "algos/discrete_replay_batch.hpp"
#include "nn/grad_check.hpp"
#include "rlrun/algos/qrdqn/qrdqn.hpp"
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

AlgorithmSetup discrete_setup(int obs_dim, int n_actions, uint64_t seed = 0) {
  return AlgorithmSetup{Space::box(-1.0f, 1.0f, {obs_dim}), Space::discrete(n_actions), 1, seed};
}

// sb3-contrib's quantile_huber_loss(current (K), target (T), sum_over_quantiles=True) for one
// sample, in double: sum over k, mean over t.
double sample_loss(const Eigen::VectorXd& current, const Eigen::VectorXd& target) {
  const auto k_count = static_cast<double>(current.size());
  double sum = 0.0;
  for (Eigen::Index t = 0; t < target.size(); ++t)
    for (Eigen::Index k = 0; k < current.size(); ++k) {
      const double tau = (static_cast<double>(k) + 0.5) / k_count;
      const double d = target(t) - current(k);
      const double huber = std::abs(d) > 1.0 ? std::abs(d) - 0.5 : 0.5 * d * d;
      sum += std::abs(tau - (d < 0.0 ? 1.0 : 0.0)) * huber;
    }
  return sum / static_cast<double>(target.size());
}

}  // namespace

TEST_CASE("QRDQN target quantiles, loss and gradient through a linear network with set weights",
          "[algos][qrdqn]") {
  QRDQN::Config cfg;
  cfg.off_policy.gamma = 0.5;
  cfg.policy.net_arch = {};
  cfg.policy.n_quantiles = 2;
  QRDQN q(cfg, discrete_setup(1, 2));
  // Outputs (view(-1, K, A): row k * A + a) = W s + b for one observation s:
  // online  theta(k=0, a=0) = s, theta(0, 1) = 2s, theta(1, 0) = 3s, theta(1, 1) = 4s
  // target  z(0, 0) = 1, z(0, 1) = 0, z(1, 0) = 1, z(1, 1) = 4   (biases, weight 0)
  q.q_net().weight(0) << 1, 2, 3, 4;
  q.q_net().bias(0).setZero();
  q.q_net_target().weight(0).setZero();
  q.q_net_target().bias(0) << 1, 0, 1, 4;
  ReplayBatch b;
  b.obs.resize(1, 1);
  b.obs << 0.5f;
  b.next_obs.resize(1, 1);
  b.next_obs << 0.0f;
  b.actions.resize(1, 1);
  b.actions << 1;
  b.rewards.resize(1);
  b.rewards << 1;
  b.dones.resize(1);
  b.dones << 0;
  const double loss = q.train_on_batch(b, 0.0f);
  // Next greedy action: means (1 + 1) / 2 = 1 for a = 0, (0 + 4) / 2 = 2 for a = 1 -> a = 1;
  // targets 1 + 0.5 * (0, 4) = (1, 3).
  CHECK(q.target_quantiles()(0, 0) == Approx(1));
  CHECK(q.target_quantiles()(1, 0) == Approx(3));
  // Current quantiles of action 1: (2s, 4s) = (1, 2), taus (0.25, 0.75).
  // (k=0, t=0): d = 0, 0. (k=0, t=1): d = 2, |0.25 - 0| * 1.5 = 0.375.
  // (k=1, t=0): d = -1, |0.75 - 1| * 0.5 = 0.125. (k=1, t=1): d = 1, 0.75 * 0.5 = 0.375.
  // Summed over k, averaged over t: (0 + 0.375 + 0.125 + 0.375) / 2 = 0.4375.
  CHECK(loss == Approx(0.4375));
  // d loss / d theta_k = -(1 / T) sum_t |tau_k - 1{d < 0}| clamp(d, -1, 1):
  // k = 0: -(0.25 * 0 + 0.25 * 1) / 2 = -0.125; k = 1: -(0.25 * -1 + 0.75 * 1) / 2 = -0.25.
  // Rows of action 1 are 1 (k = 0) and 3 (k = 1); dW = d * s, db = d; action 0 gets nothing.
  CHECK(q.q_net().bias_grad(0)(0) == Approx(0));
  CHECK(q.q_net().bias_grad(0)(1) == Approx(-0.125));
  CHECK(q.q_net().bias_grad(0)(2) == Approx(0));
  CHECK(q.q_net().bias_grad(0)(3) == Approx(-0.25));
  CHECK(q.q_net().weight_grad(0)(3, 0) == Approx(-0.125));
  CHECK(q.q_net_target().grads().isZero());
  // sb3-contrib clips nothing by default (max_grad_norm=None).
  CHECK(q.last_grad_norm() == 0.0f);
}

TEST_CASE("QRDQN loss gradient w.r.t. every quantile_net parameter matches finite differences",
          "[algos][qrdqn][gradcheck]") {
  const int n = GENERATE(13, 40);
  INFO("batch " << n);
  QRDQN::Config cfg;
  cfg.policy.net_arch = {24, 12};
  cfg.policy.n_quantiles = 5;
  cfg.off_policy.gamma = 0.9;
  const int obs_dim = 3, n_actions = 3, quantiles = 5;
  QRDQN q(cfg, discrete_setup(obs_dim, n_actions, 5));
  Rng rng(7);
  for (Eigen::Index i = 0; i < q.q_net_target().num_params(); ++i)
    q.q_net_target().params()(i) += static_cast<float>(rng.uniform(-1.5, 1.5));
  const ReplayBatch b = test::random_discrete_batch(rng, obs_dim, n_actions, n);
  const double loss = q.train_on_batch(b, 0.0f);
  const Eigen::VectorXd analytic = q.q_net().grads().cast<double>();

  // Targets re-derived in double from the target network: greedy on the quantile means.
  const Eigen::VectorXd target_params = q.q_net_target().params().cast<double>();
  std::vector<Eigen::VectorXd> targets(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd next =
        test::mlp_forward(q.q_net_target(), target_params, b.next_obs.col(j).cast<double>()).col(0);
    int greedy = 0;
    double best = -1e300;
    for (int a = 0; a < n_actions; ++a) {
      double mean = 0.0;
      for (int k = 0; k < quantiles; ++k) mean += next(k * n_actions + a) / quantiles;
      if (mean > best) best = mean, greedy = a;
    }
    targets[j].resize(quantiles);
    for (int k = 0; k < quantiles; ++k)
      targets[j](k) = b.rewards(j) + (1.0 - b.dones(j)) * 0.9 * next(k * n_actions + greedy);
    for (int k = 0; k < quantiles; ++k)
      CHECK(q.target_quantiles()(k, j) == Approx(targets[j](k)).epsilon(1e-5).margin(1e-5));
  }
  const auto double_loss = [&](const Eigen::VectorXd& p) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd out =
          test::mlp_forward(q.q_net(), p, b.obs.col(j).cast<double>()).col(0);
      const int a = static_cast<int>(b.actions(0, j));
      Eigen::VectorXd current(quantiles);
      for (int k = 0; k < quantiles; ++k) current(k) = out(k * n_actions + a);
      sum += sample_loss(current, targets[j]);
    }
    return sum / n;
  };
  const Eigen::VectorXd p0 = q.q_net().params().cast<double>();
  CHECK(double_loss(p0) == Approx(loss).epsilon(1e-5));
  require_grad_close(analytic, numeric_gradient(double_loss, p0));
}

TEST_CASE("QRDQN's Adam has eps = 0.01 / batch_size and clips only when max_grad_norm is set",
          "[algos][qrdqn]") {
  QRDQN::Config cfg;
  cfg.policy.net_arch = {8};
  cfg.policy.n_quantiles = 4;
  cfg.off_policy.batch_size = 16;
  QRDQN q(cfg, discrete_setup(2, 2, 3));
  Rng rng(1);
  const ReplayBatch b = test::random_discrete_batch(rng, 2, 2, 16);
  const Eigen::VectorXf before = q.q_net().params();
  const float lr = 1e-3f;
  q.train_on_batch(b, lr);
  // Adam's first step: m_hat = g, v_hat = g^2, so the step is lr * g / (|g| + eps).
  const Eigen::VectorXf g = q.q_net().grads();
  const double eps = 0.01 / 16;
  int distinguishable = 0;  // steps where torch's default eps 1e-8 would give another value
  for (Eigen::Index i = 0; i < g.size(); ++i) {
    const double gi = g(i);
    const double expected = -lr * gi / (std::abs(gi) + eps);
    CHECK(q.q_net().params()(i) - before(i) == Approx(expected).epsilon(1e-3).margin(1e-7));
    distinguishable += std::abs(expected + lr * gi / (std::abs(gi) + 1e-8)) > 1e-6;
  }
  CHECK(distinguishable > 0);
  CHECK(q.last_grad_norm() == 0.0f);

  cfg.max_grad_norm = 1e-4;
  QRDQN clipped(cfg, discrete_setup(2, 2, 3));
  clipped.train_on_batch(b, 0.0f);
  CHECK(clipped.last_grad_norm() > 1e-4f);
  CHECK(clipped.q_net().grads().norm() == Approx(1e-4).epsilon(1e-3));
}

TEST_CASE("QRDQN acts greedily on the mean of each action's quantiles", "[algos][qrdqn]") {
  QRDQN::Config cfg;
  cfg.policy.net_arch = {};
  cfg.policy.n_quantiles = 3;
  QRDQN q(cfg, discrete_setup(1, 2));
  // Action 0's quantiles (0, 0, 3) have the larger mean; action 1's (1, 1, 1) the larger first
  // two quantiles and median.
  q.q_net().weight(0).setZero();
  q.q_net().bias(0) << 0, 1, 0, 1, 3, 1;
  Eigen::MatrixXf obs = Eigen::MatrixXf::Zero(1, 2), actions;
  q.predict(obs, true, actions);
  CHECK(actions == (Eigen::MatrixXf(1, 2) << 0, 0).finished());
  q.q_net().bias(0) << 0, 1, 0, 1, 2.9f, 1;  // means 0.967 and 1
  q.predict(obs, true, actions);
  CHECK(actions == (Eigen::MatrixXf(1, 2) << 1, 1).finished());
}

TEST_CASE("QRDQN saves sb3-contrib-named quantile_net tensors and loads them back",
          "[algos][qrdqn]") {
  QRDQN::Config cfg;
  cfg.policy.net_arch = {16};
  cfg.policy.n_quantiles = 7;
  QRDQN a(cfg, discrete_setup(4, 3, 1));
  TensorMap t;
  a.save(t);
  for (const char* name :
       {"quantile_net.0.weight", "quantile_net.2.weight", "quantile_net.2.bias",
        "quantile_net_target.0.weight", "quantile_net_target.2.bias", "exploration_rate"})
    CHECK(t.count(name) == 1);
  CHECK(t.at("quantile_net.2.weight").shape == std::vector<int64_t>{21, 16});
  CHECK(t.at("quantile_net.2.weight").bytes == t.at("quantile_net_target.2.weight").bytes);
  QRDQN b(cfg, discrete_setup(4, 3, 2));
  b.load(t);
  CHECK(b.q_net().params() == a.q_net().params());
  t.erase("quantile_net_target.0.bias");
  CHECK_THROWS(b.load(t));
  // Defaults as sb3-contrib's QRDQN.__init__.
  const QRDQN::Config d;
  CHECK(d.learning_rate(1.0) == Approx(5e-5));
  CHECK(d.exploration_fraction == 0.005);
  CHECK(d.exploration_final_eps == 0.01);
  CHECK(d.policy.n_quantiles == 200);
  CHECK_FALSE(d.max_grad_norm.has_value());
  CHECK_THROWS_AS(
      QRDQN(d, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::box(-1.0f, 1.0f, {1}), 1, 0}),
      std::invalid_argument);
}

TEST_CASE("QRDQN trains on CartPole-v1 through the registry, deterministically, and evaluates",
          "[algos][qrdqn]") {
  testing::TempDir dir("qrdqn_smoke");
  const std::string yaml =
      "run: {name: qrdqn_smoke, seed: 3, total_timesteps: 600, out_dir: " + dir.str() +
      ", console_interval: 1000}\n"
      "env: {id: CartPole-v1, n_envs: 2}\n"
      "algo: {id: QRDQN, learning_starts: 100, batch_size: 16, "
      "train_freq: 8, gradient_steps: 2, target_update_interval: 50, "
      "policy: {net_arch: [16, 16], n_quantiles: 5}}\n";
  const auto run = [&] {
    const Experiment e =
        parse_experiment(ConfigNode::load_string(yaml, "qrdqn.yaml"), builtin_registry());
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    CHECK(outcome.timesteps == 608);
    return read_model(outcome.model_path);
  };
  const ModelFile m1 = run();
  const ModelFile m2 = run();
  CHECK(m1.meta.algorithm == "QRDQN");
  CHECK(m1.tensors.at("quantile_net.4.weight").bytes ==
        m2.tensors.at("quantile_net.4.weight").bytes);
  CHECK(m1.tensors.at("quantile_net.4.weight").shape == std::vector<int64_t>{10, 16});
  // The schedule ends at 0.5 % of training (sb3-contrib's exploration_fraction 0.005).
  CHECK(*m1.tensors.at("exploration_rate").data<double>() == Approx(0.01));
  const Experiment stored = experiment_from_model(m1, builtin_registry());
  EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
  auto loaded = algorithm_from_model(m1, stored, builtin_registry(), env->observation_space(),
                                     env->action_space());
  CHECK(evaluate_policy(*loaded, *env, 2, true, 5).returns.size() == 2);
}

// The per-update cost against DQN's on the same network (issue 45 asks for it, sb3-contrib not
// being runnable here): the zoo's CartPole (10 quantiles, batch 64) and LunarLander (170
// quantiles, batch 128) entries. FLOP as anchors.md counts them: 2 in out per layer and sample
// forward, twice that backward, 4 forwards a step (the loss's K x T pairs not counted).
TEST_CASE("QRDQN update micro-benchmark (rl-zoo CartPole and LunarLander sizes)",
          "[.bench][qrdqn_bench]") {
  struct Size {
    const char* name;
    int obs_dim, n_actions, n_quantiles, batch;
  };
  for (const Size& size : {Size{"CartPole", 4, 2, 10, 64}, Size{"LunarLander", 8, 4, 170, 128}}) {
    QRDQN::Config cfg;
    cfg.policy.net_arch = {256, 256};
    cfg.policy.n_quantiles = size.n_quantiles;
    cfg.off_policy.batch_size = size.batch;
    AlgorithmSetup setup = discrete_setup(size.obs_dim, size.n_actions, 1);
    setup.pool = &testing::test_thread_pool();
    QRDQN q(cfg, setup);
    Rng rng(1);
    const ReplayBatch b =
        test::random_discrete_batch(rng, size.obs_dim, size.n_actions, size.batch);
    for (int i = 0; i < 100; ++i) q.train_on_batch(b, 1e-6f);
    const int iters = 500;
    double best = 1e30;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < iters; ++i) q.train_on_batch(b, 1e-6f);
      best = std::min(
          best,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / iters);
    }
    const Mlp& net = q.q_net();
    double fwd = 0.0;
    for (int l = 0; l < net.num_layers(); ++l)
      fwd += 2.0 * net.layer_in(l) * net.layer_out(l) * size.batch;
    std::printf(
        "QRDQN gradient step, %s (%d-256-256-%d, batch %d, %d threads): %.1f us, %.1f "
        "GFLOP/s\n",
        size.name, size.obs_dim, size.n_actions * size.n_quantiles, size.batch,
        testing::test_thread_pool().threads(), best * 1e6, 4.0 * fwd / best * 1e-9);
    CHECK(net.params().allFinite());
  }
}

TEST_CASE("QRDQN learns CartPole-v1 (rl-zoo settings, 5e4 steps) in 2 of 3 seeds",
          "[.slow][algos][qrdqn_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) {
    testing::TempDir dir("qrdqn_slow_" + std::to_string(seed));
    Registry registry = make_builtin_registry();
    const Experiment e =
        load_experiment(std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_qrdqn.yaml",
                        {"run.out_dir=" + dir.str(), "run.seed=" + std::to_string(seed)}, registry);
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    const ModelFile model = read_model(outcome.run_dir + "/best_model.zip");
    const Experiment stored = experiment_from_model(model, builtin_registry());
    EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
    auto loaded = algorithm_from_model(model, stored, builtin_registry(), env->observation_space(),
                                       env->action_space());
    const double mean = evaluate_policy(*loaded, *env, 10, true, 0).mean_return();
    std::printf("QRDQN CartPole seed %llu: %.1f s, eval %.1f\n",
                static_cast<unsigned long long>(seed), outcome.wall_seconds, mean);
    passed += mean >= 475.0;
  }
  CHECK(passed >= 2);
}
