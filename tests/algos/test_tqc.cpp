// TQC (src/rlrun/algos/tqc/): the quantile Huber loss and the truncated target on hand-made
// numbers, one gradient step against a double re-implementation (target atoms, critic loss,
// entropy coefficient, actor loss, Polyak), the critic and actor gradients against finite
// differences, model tensors, the exported value, settings checks, and short runs through the
// registry. The rl-zoo learning bar is hidden ([.slow]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "algos/entropy_regularized_fixtures.hpp"
#include "rlrun/algos/common/quantile_huber_loss.hpp"
#include "rlrun/algos/tqc/tqc.hpp"
#include "rlrun/algos/tqc/truncated_quantiles.hpp"
#include "rlrun/nn/policy_graph.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;
using namespace rlrun::test;

namespace {

// sb3-contrib quantile_huber_loss summed (not averaged) over one sample's K x T atom pairs.
double rho_sum(const Eigen::VectorXd& current, const Eigen::VectorXd& target) {
  const auto k_count = static_cast<double>(current.size());
  double sum = 0.0;
  for (Eigen::Index k = 0; k < current.size(); ++k) {
    const double tau = (static_cast<double>(k) + 0.5) / k_count;
    for (Eigen::Index t = 0; t < target.size(); ++t) {
      const double d = target(t) - current(k);
      const double huber = std::abs(d) > 1.0 ? std::abs(d) - 0.5 : 0.5 * d * d;
      sum += std::abs(tau - (d < 0.0 ? 1.0 : 0.0)) * huber;
    }
  }
  return sum;
}

// Rewards of a few units: the target atoms spread over several Huber scales.
constexpr double kRewardScale = 2.0;

TQC::Config small_config() {
  TQC::Config c;
  c.policy.net_arch = {{8, 8}, {8, 8}};
  c.policy.n_quantiles = 5;
  c.top_quantiles_to_drop_per_net = 2;  // 2 critics x 3 atoms kept = 6 target atoms
  c.off_policy.batch_size = 6;
  c.off_policy.buffer_size = 1000;
  c.off_policy.gamma = 0.9;
  c.off_policy.tau = 0.1;
  c.ent_coef = "auto_0.5";
  return c;
}

// Critic i's atoms at x, in double with parameters p.
Eigen::VectorXd atoms(const ContinuousCritic& critic, int i, const Eigen::VectorXd& p,
                      const Eigen::VectorXd& x) {
  return mlp_forward_one(critic.q(i).net(), p, x);
}

// The mean of every critic's atoms at (s, a) with their current parameters.
ActorQ mean_atom(const TQC& tqc) {
  return [&tqc](const Eigen::VectorXd& o, const Eigen::VectorXd& a) {
    double q = 0.0;
    for (int i = 0; i < tqc.critic().n_critics(); ++i)
      q += atoms(tqc.critic(), i, params_of(tqc.critic().q(i).net()), concat(o, a)).mean();
    return q / tqc.critic().n_critics();
  };
}

}  // namespace

TEST_CASE("TQC quantile Huber loss and its gradient on hand-computed values", "[algos][tqc]") {
  // K = 2 atoms at tau = (0.25, 0.75), T = 2 target atoms, two samples.
  //   rho = |tau - 1{delta < 0}| * huber(delta), delta = z - theta,
  //   d rho / d theta = -|tau - 1{delta < 0}| * clamp(delta, -1, 1).
  // Sample 0: theta = (0, 1), z = (0.5, 3).
  //   k=0 (tau .25): delta .5 -> w .25, huber .125,  rho .03125, grad -.125
  //                  delta 3  -> w .25, huber 2.5,   rho .625,   grad -.25
  //   k=1 (tau .75): delta -.5 -> w .25, huber .125, rho .03125, grad +.125
  //                  delta 2   -> w .75, huber 1.5,  rho 1.125,  grad -.75
  //   sum 1.8125; d/dtheta0 = -.375, d/dtheta1 = -.625.
  // Sample 1: theta = (2, -1), z = (1, 1): |delta| = 1 is still the quadratic branch.
  //   k=0: delta -1 (twice) -> w .75, huber .5, rho .375, grad +.75 each
  //   k=1: delta 2 (twice)  -> w .75, huber 1.5, rho 1.125, grad -.75 each
  //   sum 3.0; d/dtheta0 = 1.5, d/dtheta1 = -1.5.
  // sb3-contrib's mean over batch x critics x K x T = 2 x 1 x 2 x 2 = 8 pairs: 4.8125 / 8.
  Eigen::MatrixXf current(2, 2), target(2, 2), grad, rho;
  current << 0.0f, 2.0f,  //
      1.0f, -1.0f;
  target << 0.5f, 1.0f,  //
      3.0f, 1.0f;
  const double loss = quantile_huber_loss(current, target, 1.0f / 8.0f, grad, rho);
  CHECK(loss == Approx(0.6015625).epsilon(1e-7));
  // Per atom, summed over the targets: (.65625, 1.15625) and (.75, 2.25), scaled.
  CHECK(rho(0, 0) == Approx(0.65625 / 8));
  CHECK(rho(1, 0) == Approx(1.15625 / 8));
  CHECK(rho(0, 1) == Approx(0.75 / 8));
  CHECK(rho(1, 1) == Approx(2.25 / 8));
  CHECK(grad(0, 0) == Approx(-0.375 / 8));
  CHECK(grad(1, 0) == Approx(-0.625 / 8));
  CHECK(grad(0, 1) == Approx(1.5 / 8));
  CHECK(grad(1, 1) == Approx(-1.5 / 8));

  // Exact quantiles of the targets cost nothing at the median: one atom, tau = .5, z = theta.
  Eigen::MatrixXf one(1, 1);
  one << 0.3f;
  CHECK(quantile_huber_loss(one, one, 1.0f, grad, rho) == 0.0);
  CHECK(grad(0, 0) == 0.0f);
  CHECK_THROWS_AS(quantile_huber_loss(current, Eigen::MatrixXf::Zero(2, 3), 1.0f, grad, rho),
                  std::invalid_argument);
}

TEST_CASE("TQC quantile Huber loss gradient matches finite differences",
          "[algos][tqc][gradcheck]") {
  Rng rng(3);
  const int k_count = 4, t_count = 7, n = 5;
  const Eigen::MatrixXf current = random_matrix(rng, k_count, n, 1.5);
  const Eigen::MatrixXf target = random_matrix(rng, t_count, n, 1.5);
  const float scale = 1.0f / static_cast<float>(n * k_count * t_count);
  Eigen::MatrixXf grad, rho;
  const double loss = quantile_huber_loss(current, target, scale, grad, rho);
  const auto loss_of = [&](const Eigen::VectorXd& flat) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      sum += rho_sum(flat.segment(j * k_count, k_count), target.col(j).cast<double>());
    return sum * scale;
  };
  const Eigen::VectorXd flat =
      Eigen::Map<const Eigen::VectorXf>(current.data(), current.size()).cast<double>();
  CHECK(loss == Approx(loss_of(flat)).epsilon(1e-5));
  require_grad_close(Eigen::Map<const Eigen::VectorXf>(grad.data(), grad.size()).cast<double>(),
                     numeric_gradient(loss_of, flat));
}

TEST_CASE("TQC target: the critics' atoms pooled, sorted, and the largest dropped",
          "[algos][tqc]") {
  // 2 critics x 3 atoms, 2 samples (a column each).
  Eigen::MatrixXf q0(3, 2), q1(3, 2), out;
  q0 << 3.0f, -1.0f,  //
      1.0f, -1.0f,    //
      5.0f, 4.0f;
  q1 << 2.0f, 7.0f,  //
      6.0f, -2.0f,   //
      0.0f, 0.5f;
  std::vector<float> pooled;
  // Drop 1 per net: n_target = 6 - 2 = 4.
  // Sample 0 pooled (3, 1, 5, 2, 6, 0) -> sorted (0, 1, 2, 3, 5, 6) -> (0, 1, 2, 3).
  // Sample 1 pooled (-1, -1, 4, 7, -2, .5) -> (-2, -1, -1, .5, 4, 7) -> (-2, -1, -1, .5).
  truncated_quantiles({&q0, &q1}, 4, out, pooled);
  Eigen::MatrixXf expected(4, 2);
  expected << 0.0f, -2.0f,  //
      1.0f, -1.0f,          //
      2.0f, -1.0f,          //
      3.0f, 0.5f;
  CHECK(out == expected);
  // Nothing dropped: the whole pooled mixture in order.
  truncated_quantiles({&q0, &q1}, 6, out, pooled);
  Eigen::MatrixXf all(6, 2);
  all << 0.0f, -2.0f,  //
      1.0f, -1.0f,     //
      2.0f, -1.0f,     //
      3.0f, 0.5f,      //
      5.0f, 4.0f,      //
      6.0f, 7.0f;
  CHECK(out == all);
  CHECK_THROWS_AS(truncated_quantiles({&q0, &q1}, 0, out, pooled), std::invalid_argument);
  CHECK_THROWS_AS(truncated_quantiles({&q0, &q1}, 7, out, pooled), std::invalid_argument);

  // Through TQC: n_target_quantiles = n_critics * (n_quantiles - drop).
  TQC::Config cfg = small_config();
  cfg.policy.n_critics = 3;
  TQC tqc(cfg, box_setup(3, 1));
  CHECK(tqc.n_target_quantiles() == 3 * (5 - 2));
}

TEST_CASE(
    "TQC train step: target atoms, critic loss, entropy coefficient, actor loss and Polyak "
    "update match a double re-computation",
    "[algos][tqc]") {
  // 6: one core's batch; 40: split over two (nn/batch_split.hpp).
  const int n = GENERATE(6, 40);
  INFO("batch " << n);
  const int obs_dim = 3, act_dim = 2, n_critics = 2, k_count = 5, n_target = 6;
  TQC tqc(small_config(), box_setup(obs_dim, act_dim));
  REQUIRE(tqc.n_target_quantiles() == n_target);
  Rng rng(11);
  ReplayBatch b = random_batch(rng, obs_dim, act_dim, n, kRewardScale);
  const StepStart start(tqc);
  const double alpha = start.alpha;
  CHECK(alpha == Approx(0.5));

  const float lr = 1e-3f;
  const EntropyRegularizedStepStats stats = tqc.train_on_batch(b, lr, true);
  const Eigen::MatrixXf& y = tqc.last_target_quantiles();
  REQUIRE(y.rows() == n_target);
  double critic_loss = 0.0;
  for (int j = 0; j < n; ++j) {
    INFO("sample " << j);
    const auto [a, logp] =
        actor_sample(tqc.actor().net(), start.actor, act_dim, b.next_obs.col(j).cast<double>(),
                     tqc.last_next_noise().col(j).cast<double>());
    const Eigen::VectorXd x = concat(b.next_obs.col(j).cast<double>(), a);
    std::vector<double> pooled;
    for (int i = 0; i < n_critics; ++i) {
      const Eigen::VectorXd z = atoms(tqc.critic_target(), i, start.targets[i], x);
      pooled.insert(pooled.end(), z.data(), z.data() + z.size());
    }
    std::sort(pooled.begin(), pooled.end());
    Eigen::VectorXd expected(n_target);
    for (int t = 0; t < n_target; ++t)
      expected(t) = b.rewards(j) + (1.0 - b.dones(j)) * 0.9 * (pooled[t] - alpha * logp);
    for (int t = 0; t < n_target; ++t)
      CHECK(y(t, j) == Approx(expected(t)).epsilon(1e-4).margin(1e-5));
    const Eigen::VectorXd xa = concat(b.obs.col(j).cast<double>(), b.actions.col(j).cast<double>());
    for (int i = 0; i < n_critics; ++i)
      critic_loss += rho_sum(atoms(tqc.critic(), i, start.critics[i], xa), expected);
  }
  critic_loss /= static_cast<double>(n * n_critics * k_count * n_target);
  CHECK(stats.critic_loss == Approx(critic_loss).epsilon(1e-4));

  // Actor loss mean(alpha log pi(a_pi|s) - mean of all atoms at (s, a_pi)) with the stepped
  // critics.
  check_actor_temperature_and_targets(tqc, start, b, lr, 0.1, stats, mean_atom(tqc));
}

TEST_CASE(
    "TQC critic and actor gradients of a train step match finite differences, through the "
    "quantile critics and the squashed Gaussian",
    "[algos][tqc][gradcheck]") {
  const int n = GENERATE(8, 40);
  INFO("batch " << n);
  const int obs_dim = 3, act_dim = 2, n_critics = 2, k_count = 5;
  TQC::Config cfg = small_config();
  cfg.ent_coef = "0.3";
  TQC tqc(cfg, box_setup(obs_dim, act_dim, 9));
  Rng rng(5);
  const ReplayBatch b = random_batch(rng, obs_dim, act_dim, n, kRewardScale);
  // Learning rate 0: the step leaves every parameter where it was and its gradients in place.
  tqc.train_on_batch(b, 0.0f, false);
  const double alpha = 0.3;
  const Eigen::MatrixXf& y = tqc.last_target_quantiles();
  const auto n_target = static_cast<int>(y.rows());

  // critic_loss = mean over (batch, critics, K, T) of rho, the target fixed: only critic i's
  // terms depend on its parameters.
  for (int i = 0; i < n_critics; ++i) {
    const auto loss_of = [&](const Eigen::VectorXd& p) {
      double sum = 0.0;
      for (int j = 0; j < n; ++j)
        sum += rho_sum(atoms(tqc.critic(), i, p,
                             concat(b.obs.col(j).cast<double>(), b.actions.col(j).cast<double>())),
                       y.col(j).cast<double>());
      return sum / static_cast<double>(n * n_critics * k_count * n_target);
    };
    const Eigen::VectorXd p = params_of(tqc.critic().q(i).net());
    require_grad_close(tqc.critic().q(i).grads().cast<double>(), numeric_gradient(loss_of, p));
  }

  // actor_loss = mean(alpha log pi(a|s) - mean_ik Q_ik(s, a)), a = tanh(mu + std eps).
  const auto loss_of = [&](const Eigen::VectorXd& p) {
    return actor_loss(tqc, p, b, alpha, mean_atom(tqc));
  };
  const Eigen::VectorXd p = params_of(tqc.actor().net());
  require_grad_close(tqc.actor().net().grads().cast<double>(), numeric_gradient(loss_of, p));
}

TEST_CASE("TQC model tensors use sb3-contrib's names and load back, and the exported value",
          "[algos][tqc]") {
  TQC::Config cfg = small_config();
  TQC a(cfg, box_setup(3, 1, 1));
  Rng rng(4);
  // Targets now differ from init.
  a.train_on_batch(random_batch(rng, 3, 1, 6, kRewardScale), 1e-2f, true);
  TensorMap t;
  a.save(t);
  check_sb3_tensor_names(t);
  CHECK(t.at("critic.qf0.4.weight").shape == std::vector<int64_t>{5, 8});  // n_quantiles out
  CHECK(t.at("critic_target.qf1.4.bias").shape == std::vector<int64_t>{5});

  TQC b(cfg, box_setup(3, 1, 99));
  b.load(t);
  const Eigen::MatrixXf obs = random_matrix(rng, 3, 4);
  Eigen::MatrixXf pa, pb;
  a.predict(obs, true, pa);
  b.predict(obs, true, pb);
  CHECK(pa == pb);
  CHECK(b.critic_target().q(1).params() == a.critic_target().q(1).params());
  CHECK(b.ent_coef().log_value() == a.ent_coef().log_value());
  // Another n_quantiles does not load.
  TQC::Config other = cfg;
  other.policy.n_quantiles = 4;
  TQC c(other, box_setup(3, 1, 99));
  CHECK_THROWS(c.load(t));
  t.erase("critic.qf1.2.bias");
  CHECK_THROWS(b.load(t));

  // The exported graph: the deterministic action, and as the value the mean of every atom of
  // every critic at (s, that action).
  PolicyGraph graph;
  graph.add_input("obs", 3);
  a.export_policy(graph, "obs", true);
  const auto values = evaluate_graph(graph, {obs});
  CHECK((values.at(graph.action()) - pa).cwiseAbs().maxCoeff() < 1e-5f);
  Eigen::MatrixXf scaled;
  a.actor().mode(obs, scaled);
  a.critic().forward(obs, scaled);
  const Eigen::RowVectorXf q =
      (a.critic().q(0).output().colwise().sum() + a.critic().q(1).output().colwise().sum()) / 10.0f;
  CHECK((values.at(graph.value()) - q).cwiseAbs().maxCoeff() < 1e-5f);
}

TEST_CASE("TQC rejects bad settings with a message", "[algos][tqc]") {
  TQC::Config c;
  c.ent_coef = "sometimes";
  CHECK_THROWS_AS(TQC(c, box_setup(3, 1)), std::invalid_argument);
  c = TQC::Config();
  c.target_update_interval = 0;
  CHECK_THROWS_AS(TQC(c, box_setup(3, 1)), std::invalid_argument);
  c = TQC::Config();
  c.top_quantiles_to_drop_per_net = 25;  // of 25: no atom left
  CHECK_THROWS_AS(TQC(c, box_setup(3, 1)), std::invalid_argument);
  const ConfigProblems problems = TQC::check(c, box_setup(3, 1));
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].key == "top_quantiles_to_drop_per_net");
  CHECK_THAT(problems[0].message, Catch::Contains("[0, 24]"));
  c.top_quantiles_to_drop_per_net = 24;
  CHECK(TQC::check(c, box_setup(3, 1)).empty());
  c = TQC::Config();
  CHECK_THROWS_AS(TQC(c, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::discrete(2), 1, 0}),
                  std::invalid_argument);
  CHECK_THROWS_AS(TQC(c, AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}),
                                        Space::box(-std::numeric_limits<float>::infinity(),
                                                   std::numeric_limits<float>::infinity(), {1}),
                                        1, 0}),
                  std::invalid_argument);
  // Through the experiment parser: the key and its bound.
  const auto parse_error = [](const std::string& algo) {
    try {
      parse_experiment(ConfigNode::load_string("run: {name: x, total_timesteps: 100}\n"
                                               "env: {id: Pendulum-v1}\n"
                                               "algo: {id: TQC" +
                                                   algo + "}\n",
                                               "tqc.yaml"),
                       builtin_registry());
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(parse_error(", top_quantiles_to_drop_per_net: 30"),
             Catch::Contains("top_quantiles_to_drop_per_net"));
  CHECK_THAT(parse_error(", policy: {n_quantile: 5}"), Catch::Contains("n_quantiles"));
  CHECK(parse_error(", top_quantiles_to_drop_per_net: 5, policy: {n_quantiles: 10}") == "");
}

namespace {
double evaluate_model(const std::string& model_path, int episodes, uint64_t seed) {
  return test::evaluate_model(read_model(model_path), episodes, seed).mean_return();
}
}  // namespace

TEST_CASE("TQC trains a few hundred steps on Pendulum-v1 through the registry, deterministically",
          "[algos][tqc]") {
  testing::TempDir dir("tqc_smoke");
  const auto run = [&](uint64_t seed, const std::string& extra) {
    const Experiment e = pendulum_experiment(
        "TQC", dir.str(), 400, seed,
        ", learning_starts: 100, batch_size: 32, policy: {net_arch: [32, 32], n_quantiles: 10}" +
            extra);
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    CHECK(outcome.timesteps == 400);
    return outcome.model_path;
  };
  const ModelFile m1 = read_model(run(3, ""));
  const ModelFile m2 = read_model(run(3, ""));
  CHECK(m1.meta.algorithm == "TQC");
  CHECK(m1.tensors.at("actor.mu.weight").bytes == m2.tensors.at("actor.mu.weight").bytes);
  CHECK(m1.tensors.at("critic.qf1.4.weight").bytes == m2.tensors.at("critic.qf1.4.weight").bytes);
  CHECK(m1.tensors.at("log_ent_coef").bytes == m2.tensors.at("log_ent_coef").bytes);
  CHECK(m1.tensors.at("critic.qf0.4.weight").shape == std::vector<int64_t>{10, 32});
  // 300 updates of the learned alpha from 1.0 with lr 3e-4: it moved, not beyond Adam's ~lr
  // per step.
  const float log_alpha = *m1.tensors.at("log_ent_coef").data<float>();
  CHECK(log_alpha != 0.0f);
  CHECK(std::abs(log_alpha) <= 300 * 3e-4 * 1.01);
  // gSDE runs too (SAC's exploration matrices and resets); the model evaluates a whole episode.
  const std::string gsde = run(3, ", use_sde: true, sde_sample_freq: 4");
  CHECK(read_model(gsde).tensors.count("actor.log_std") == 1);
  CHECK(std::isfinite(evaluate_model(gsde, 1, 5)));
}

// Small networks and a short budget (~10 s on 2 cores): a bar well above a random policy's
// -1200 that the zoo settings (configs/pendulum_tqc.yaml, [.slow] below) clear by far.
TEST_CASE("TQC learns Pendulum-v1 with small networks in 8000 steps", "[algos][tqc][learning]") {
  testing::TempDir dir("tqc_learn");
  const Experiment e =
      pendulum_experiment("TQC", dir.str(), 8000, 1,
                          ", learning_rate: 1.0e-3, batch_size: 128, policy: {net_arch: [64, 64]}");
  const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
  const double mean = evaluate_model(outcome.model_path, 10, 1001);
  std::printf("TQC Pendulum-v1 8000 steps, 64x64: %.1f s, eval %.1f\n", outcome.wall_seconds, mean);
  CHECK(mean >= -400.0);
}

TEST_CASE("TQC learns Pendulum-v1 (rl-zoo settings, 2e4 steps) in 2 of 3 seeds",
          "[.slow][algos][tqc_slow]") {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) {
    testing::TempDir dir("tqc_slow_" + std::to_string(seed));
    Registry registry = make_builtin_registry();
    const Experiment e =
        load_experiment(std::string(RLRUN_SOURCE_DIR) + "/configs/pendulum_tqc.yaml",
                        {"run.out_dir=" + dir.str(), "run.seed=" + std::to_string(seed),
                         "run.console_interval=1000000"},
                        registry);
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    const double mean = evaluate_model(outcome.model_path, 10, 1000 + seed);
    std::printf("pendulum_tqc.yaml seed %llu: %.1f s, eval %.1f\n",
                static_cast<unsigned long long>(seed), outcome.wall_seconds, mean);
    passed += mean >= -200.0;
  }
  CHECK(passed >= 2);
}
