// SAC (src/rlrun/algos/sac/): one gradient step against double re-implementations (the soft
// Bellman target, the critic, actor and entropy-coefficient losses and steps, Polyak), the
// critic and actor gradients against finite differences, action scaling, model tensors, and
// short runs through the registry. The learning bars are
// hidden ([.slow]); the update micro-benchmark too ([.bench]).
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <vector>

#include "algos/entropy_regularized_fixtures.hpp"
#include "rlrun/algos/common/action_scaling.hpp"
#include "rlrun/algos/common/entropy_coefficient.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;
using namespace rlrun::test;

namespace {

SAC::Config small_config() {
  SAC::Config c;
  c.policy.net_arch = {{8, 8}, {8, 8}};
  c.off_policy.batch_size = 6;
  c.off_policy.buffer_size = 1000;
  c.off_policy.gamma = 0.9;
  c.off_policy.tau = 0.1;
  c.ent_coef = "auto_0.5";
  return c;
}

// Q_i(x) in double with critic i's parameters p.
double q_value(const ContinuousCritic& critic, int i, const Eigen::VectorXd& p,
               const Eigen::VectorXd& x) {
  return mlp_forward_one(critic.q(i).net(), p, x)(0);
}

// min_i Q_i(s, a) with the critics' current parameters.
ActorQ min_q(const SAC& sac) {
  return [&sac](const Eigen::VectorXd& o, const Eigen::VectorXd& a) {
    double q = std::numeric_limits<double>::infinity();
    for (int i = 0; i < sac.critic().n_critics(); ++i)
      q = std::min(q, q_value(sac.critic(), i, params_of(sac.critic().q(i).net()), concat(o, a)));
    return q;
  };
}

}  // namespace

TEST_CASE(
    "SAC train step: critic target, critic loss, entropy coefficient, actor loss and Polyak "
    "update match a double re-computation",
    "[algos][sac]") {
  // 6: one core's batch; 40: split over two (nn/batch_split.hpp).
  const int n = GENERATE(6, 40);
  INFO("batch " << n);
  const int obs_dim = 3, act_dim = 2;
  SAC sac(small_config(), box_setup(obs_dim, act_dim));
  Rng rng(11);
  ReplayBatch b = random_batch(rng, obs_dim, act_dim, n);
  const StepStart start(sac);
  const double alpha = start.alpha;
  CHECK(alpha == Approx(0.5));

  const float lr = 1e-3f;
  const EntropyRegularizedStepStats stats = sac.train_on_batch(b, lr, true);
  const Eigen::MatrixXf& noise = sac.last_next_noise();
  const Eigen::MatrixXf& y = sac.last_critic_target();
  double critic_loss = 0.0;
  for (int j = 0; j < n; ++j) {
    const auto [a, logp] =
        actor_sample(sac.actor().net(), start.actor, act_dim, b.next_obs.col(j).cast<double>(),
                     noise.col(j).cast<double>());
    const Eigen::VectorXd x = concat(b.next_obs.col(j).cast<double>(), a);
    const double min_q = std::min(q_value(sac.critic_target(), 0, start.targets[0], x),
                                  q_value(sac.critic_target(), 1, start.targets[1], x));
    const double expected = b.rewards(j) + (1.0 - b.dones(j)) * 0.9 * (min_q - alpha * logp);
    INFO("sample " << j);
    CHECK(y(0, j) == Approx(expected).epsilon(1e-4).margin(1e-5));
    const Eigen::VectorXd xa = concat(b.obs.col(j).cast<double>(), b.actions.col(j).cast<double>());
    for (int i = 0; i < 2; ++i) {
      const double d = q_value(sac.critic(), i, start.critics[i], xa) - y(0, j);
      critic_loss += 0.5 * d * d / n;
    }
  }
  CHECK(stats.critic_loss == Approx(critic_loss).epsilon(1e-4));
  // Actor loss mean(alpha log pi(a_pi|s) - min_i Q_i(s, a_pi)) with the stepped critics.
  check_actor_temperature_and_targets(sac, start, b, lr, 0.1, stats, min_q(sac));
}

TEST_CASE(
    "SAC critic and actor gradients of a train step match finite differences, through the "
    "critics and the squashed Gaussian",
    "[algos][sac][gradcheck]") {
  const int n = GENERATE(8, 40);
  INFO("batch " << n);
  const int obs_dim = 3, act_dim = 2;
  SAC::Config cfg = small_config();
  cfg.ent_coef = "0.3";
  SAC sac(cfg, box_setup(obs_dim, act_dim, 9));
  // Second log_std head pushed below LOG_STD_MIN: the clamp must cut its gradient. (Below, not
  // above: at std = e^2 tanh saturates and float32's 1 - a^2 loses the digits a finite
  // difference in double would compare against.)
  const int last = sac.actor().net().num_layers() - 1;
  sac.actor().net().bias(last)(act_dim + 1) = -25.0f;
  Rng rng(5);
  const ReplayBatch b = random_batch(rng, obs_dim, act_dim, n);
  // Learning rate 0: the step leaves every parameter where it was and its gradients in place.
  sac.train_on_batch(b, 0.0f, false);
  const double alpha = 0.3;

  // critic_loss = 0.5 sum_i mse(Q_i(s, a), y), y fixed: only critic i's term depends on it.
  const Eigen::MatrixXf& y = sac.last_critic_target();
  for (int i = 0; i < 2; ++i) {
    const auto loss_of = [&](const Eigen::VectorXd& p) {
      double sum = 0.0;
      for (int j = 0; j < n; ++j) {
        const double d =
            q_value(sac.critic(), i, p,
                    concat(b.obs.col(j).cast<double>(), b.actions.col(j).cast<double>())) -
            y(0, j);
        sum += d * d;
      }
      return 0.5 * sum / n;
    };
    const Eigen::VectorXd p = params_of(sac.critic().q(i).net());
    require_grad_close(sac.critic().q(i).grads().cast<double>(), numeric_gradient(loss_of, p));
  }

  // actor_loss = mean(alpha log pi(a|s) - min_i Q_i(s, a)), a = tanh(mu + std eps), eps fixed.
  const auto loss_of = [&](const Eigen::VectorXd& p) {
    return actor_loss(sac, p, b, alpha, min_q(sac));
  };
  const Eigen::VectorXd p = params_of(sac.actor().net());
  require_grad_close(sac.actor().net().grads().cast<double>(), numeric_gradient(loss_of, p));
  // The clamped head gets exactly no gradient.
  CHECK(sac.actor().net().bias_grad(last)(act_dim + 1) == 0.0f);
  CHECK(sac.actor().net().bias_grad(last)(act_dim) != 0.0f);
}

TEST_CASE("SAC entropy coefficient: parsing, initial value and target", "[algos][sac]") {
  SECTION("auto starts at 1 and targets -dim(A)") {
    EntropyCoefficient e("auto", "auto", 3);
    CHECK(e.learned());
    CHECK(e.value() == Approx(1.0));
    CHECK(e.target_entropy() == -3.0f);
  }
  SECTION("fixed coefficients and bad values") {
    EntropyCoefficient e("0.2", "auto", 1);
    CHECK_FALSE(e.learned());
    CHECK(e.value() == 0.2f);
    CHECK_THROWS_AS(EntropyCoefficient("autox", "auto", 1), std::invalid_argument);
    CHECK_THROWS_AS(EntropyCoefficient("auto_-1", "auto", 1), std::invalid_argument);
    CHECK_THROWS_AS(EntropyCoefficient("auto_", "auto", 1), std::invalid_argument);
    CHECK_THROWS_AS(EntropyCoefficient("abc", "auto", 1), std::invalid_argument);
    CHECK_THROWS_AS(EntropyCoefficient("auto", "high", 1), std::invalid_argument);
  }
}

TEST_CASE("SAC action scaling: [low, high] <-> [-1, 1] round trip and env actions in bounds",
          "[algos][sac]") {
  const Space space = Space::box({-2.0f, 0.0f}, {2.0f, 5.0f}, {2});
  Eigen::MatrixXf actions(2, 3), scaled, back;
  actions << -2.0f, 0.0f, 1.5f,  //
      0.0f, 2.5f, 5.0f;
  scale_actions(space, actions, scaled);
  CHECK(scaled(0, 0) == Approx(-1.0));
  CHECK(scaled(1, 1) == Approx(0.0));
  CHECK(scaled(1, 2) == Approx(1.0));
  unscale_actions(space, scaled, back);
  CHECK((back - actions).cwiseAbs().maxCoeff() < 1e-6f);

  // Through SAC: warmup samples, policy samples with noise, and predict stay consistent.
  SAC::Config cfg = small_config();
  cfg.action_noise.noise_type = "normal";
  cfg.action_noise.noise_std = 0.5;
  SAC sac(cfg, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), space, 1, 3});
  Rng rng(2);
  const Eigen::MatrixXf obs = random_matrix(rng, 3, 1);
  Eigen::MatrixXf env_actions, buffer_actions, expected;
  for (bool warmup : {true, false}) {
    for (int k = 0; k < 50; ++k) {
      sac.select_actions(obs, warmup, env_actions, buffer_actions);
      CHECK(buffer_actions.cwiseAbs().maxCoeff() <= 1.0f);
      unscale_actions(space, buffer_actions, expected);
      CHECK((env_actions - expected).cwiseAbs().maxCoeff() < 1e-5f);
      CHECK(space.contains(std::span<const float>(env_actions.data(), 2)));
    }
  }
  // Deterministic predict = unscale(tanh(mu)).
  Eigen::MatrixXf predicted, mode(2, 1);
  sac.predict(obs, true, predicted);
  sac.actor().mode(obs, mode);
  unscale_actions(space, mode, expected);
  CHECK((predicted - expected).cwiseAbs().maxCoeff() < 1e-5f);
}

TEST_CASE("SAC model tensors use SB3's names and load back", "[algos][sac]") {
  SAC::Config cfg = small_config();
  SAC a(cfg, box_setup(3, 1, 1));
  Rng rng(4);
  a.train_on_batch(random_batch(rng, 3, 1, 6), 1e-2f, true);  // targets now differ from init
  TensorMap t;
  a.save(t);
  check_sb3_tensor_names(t);
  CHECK(t.at("actor.mu.weight").shape == std::vector<int64_t>{1, 8});

  SAC b(cfg, box_setup(3, 1, 99));
  b.load(t);
  const Eigen::MatrixXf obs = random_matrix(rng, 3, 4);
  Eigen::MatrixXf pa, pb;
  a.predict(obs, true, pa);
  b.predict(obs, true, pb);
  CHECK(pa == pb);
  CHECK(b.critic_target().q(1).params() == a.critic_target().q(1).params());
  CHECK(b.ent_coef().log_value() == a.ent_coef().log_value());
  t.erase("critic.qf1.2.bias");
  CHECK_THROWS(b.load(t));
}

TEST_CASE(
    "SAC trains a few hundred steps on Pendulum-v1 through the registry, "
    "deterministically",
    "[algos][sac]") {
  testing::TempDir dir("sac_smoke");
  const auto run = [&](uint64_t seed) {
    const Experiment e =
        pendulum_experiment("SAC", dir.str(), 400, seed,
                            ", learning_starts: 100, batch_size: 32, policy: {net_arch: [32, 32]}");
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    CHECK(outcome.timesteps == 400);
    return read_model(outcome.model_path);
  };
  const ModelFile m1 = run(3);
  const ModelFile m2 = run(3);
  CHECK(m1.tensors.at("actor.mu.weight").bytes == m2.tensors.at("actor.mu.weight").bytes);
  CHECK(m1.tensors.at("log_ent_coef").bytes == m2.tensors.at("log_ent_coef").bytes);
  // 300 updates of the learned alpha from 1.0 with lr 3e-4: it moved, and not beyond Adam's
  // ~lr per step.
  const float log_alpha = *m1.tensors.at("log_ent_coef").data<float>();
  CHECK(log_alpha != 0.0f);
  CHECK(std::abs(log_alpha) <= 300 * 3e-4 * 1.01);

  const EvalResult r = evaluate_model(m1, 1, 5);
  REQUIRE(r.returns.size() == 1);
  CHECK(r.lengths[0] == 200);
}

TEST_CASE("SAC rejects bad settings with a message", "[algos][sac]") {
  SAC::Config c;
  c.ent_coef = "sometimes";
  CHECK_THROWS_AS(SAC(c, box_setup(3, 1)), std::invalid_argument);
  c = SAC::Config();
  c.target_update_interval = 0;
  CHECK_THROWS_AS(SAC(c, box_setup(3, 1)), std::invalid_argument);
  c = SAC::Config();
  CHECK_THROWS_AS(SAC(c, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::discrete(2), 1, 0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(SAC(c, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}),
                                        Space::box(-std::numeric_limits<float>::infinity(),
                                                   std::numeric_limits<float>::infinity(), {1}),
                                        1, 0}),
                  std::invalid_argument);
}

// ---- hidden: speed and learning bars ------------------------------------------------------

namespace {
// Network FLOPs of one SAC gradient step as counted in anchors.md (2 in out per layer and
// sample forward, twice that backward), for what train_on_batch runs: actor forward on s' and
// s, actor backward (4 forward-equivalents); per critic: target forward, forward + backward
// (critic loss), forward + input-only backward (actor loss) (6). anchors.md's 10.9 TFLOP for
// 2e4 steps is this count.
double sac_step_flops(const SAC& sac, int batch) {
  const auto fwd = [&](const Mlp& m) {
    double f = 0.0;
    for (int l = 0; l < m.num_layers(); ++l) f += 2.0 * m.layer_in(l) * m.layer_out(l) * batch;
    return f;
  };
  double flops = 4.0 * fwd(sac.actor().net());
  for (int i = 0; i < sac.critic().n_critics(); ++i) flops += 6.0 * fwd(sac.critic().q(i).net());
  return flops;
}
}  // namespace

TEST_CASE("SAC update micro-benchmark (rl-zoo Pendulum sizes)", "[.bench][sac_bench]") {
  SAC::Config cfg;  // 256x256, batch 256
  AlgorithmSetup setup = box_setup(3, 1);
  setup.pool = &testing::test_thread_pool();
  SAC sac(cfg, setup);
  Rng rng(1);
  const ReplayBatch b = random_batch(rng, 3, 1, 256);
  for (int i = 0; i < 50; ++i) sac.train_on_batch(b, 1e-3f, true);
  const int iters = 400;
  double best = 1e30, best_cpu = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    for (int i = 0; i < iters; ++i) sac.train_on_batch(b, 1e-3f, true);
    best_cpu = std::min(best_cpu, static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / iters);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / iters);
  }
  const double flops = sac_step_flops(sac, 256);
  // Wall time is what a run takes; process CPU time (both threads) is steadier on a shared
  // machine. Percentages are of one core's 102 GFLOP/s.
  std::printf(
      "SAC gradient step (3-256-256-2 actor, 2x 4-256-256-1 critics, batch 256, %d threads): "
      "%.0f us wall, "
      "%.0f us CPU, %.1f MFLOP, %.1f GFLOP/s wall (%.0f%% of 102), %.1f GFLOP/s per CPU-s "
      "(%.0f%%)\n",
      testing::test_thread_pool().threads(), best * 1e6, best_cpu * 1e6, flops * 1e-6,
      flops / best * 1e-9, flops / best * 1e-9 / 102 * 100, flops / best_cpu * 1e-9,
      flops / best_cpu * 1e-9 / 102 * 100);
  CHECK(sac.actor().net().params().allFinite());
}

namespace {
double train_and_evaluate(const std::string& config, uint64_t seed) {
  testing::TempDir dir("sac_slow_" + std::to_string(seed));
  Registry registry = make_builtin_registry();
  Experiment e = load_experiment(
      std::string(RLRUN_SOURCE_DIR) + "/configs/" + config,
      {"run.out_dir=" + dir.str(), "run.seed=" + std::to_string(seed), "run.console_interval=1000"},
      registry);
  const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
  const double mean = evaluate_model(read_model(outcome.model_path), 10, 1000 + seed).mean_return();
  std::printf("%s seed %llu: %.1f s, eval %.1f\n", config.c_str(),
              static_cast<unsigned long long>(seed), outcome.wall_seconds, mean);
  return mean;
}
}  // namespace

TEST_CASE("SAC learns Pendulum-v1 (rl-zoo settings, 2e4 steps) in 2 of 3 seeds",
          "[.slow][algos][sac_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) passed += train_and_evaluate("pendulum_sac.yaml", seed) >= -200.0;
  CHECK(passed >= 2);
}

TEST_CASE("SAC learns MountainCarContinuous-v0 in 2 of 3 seeds", "[.slow][algos][sac_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3})
    passed += train_and_evaluate("mountaincarcontinuous_sac.yaml", seed) >= 90.0;
  CHECK(passed >= 2);
}
