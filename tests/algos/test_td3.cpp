// TD3 and DDPG (SB3 td3/td3.py, ddpg/ddpg.py): the critic target and its smoothing noise, the
// critic and actor gradients of a train step against finite differences of independent
// double-precision forward passes,
// policy_delay, DDPG's settings, registry smoke runs and (hidden, [.slow]) rl-zoo learning bars.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <regex>
#include <string>
#include <vector>

#include "nn/grad_check.hpp"
#include "rlrun/algos/ddpg/ddpg.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;

namespace {

constexpr int kObsDim = 3;
constexpr int kActDim = 2;

AlgorithmSetup small_setup(uint64_t seed = 7) {
  return AlgorithmSetup{Space::box(-1.0f, 1.0f, {kObsDim}),
                        Space::box({-2.0f, 0.0f}, {2.0f, 1.0f}, {kActDim}), 1, seed};
}

TD3::Config small_config() {
  TD3::Config c;
  c.policy.net_arch = {{6, 5}, {6, 5}};
  c.off_policy.batch_size = 8;
  c.off_policy.gamma = 0.9;
  c.off_policy.tau = 0.1;
  return c;
}

ReplayBatch random_batch(int n, uint64_t seed) {
  Rng rng(seed);
  auto uniform = [&rng](Eigen::Index rows, Eigen::Index cols, double lo, double hi) {
    Eigen::MatrixXf m(rows, cols);
    for (Eigen::Index k = 0; k < m.size(); ++k)
      m.data()[k] = static_cast<float>(rng.uniform(lo, hi));
    return m;
  };
  ReplayBatch b;
  b.obs = uniform(kObsDim, n, -1, 1);
  b.next_obs = uniform(kObsDim, n, -1, 1);
  b.actions = uniform(kActDim, n, -1, 1);
  b.rewards = uniform(1, n, -2, 1);
  b.dones.resize(n);
  for (int j = 0; j < n; ++j) b.dones(j) = j % 3 == 0 ? 1.0f : 0.0f;
  return b;
}

Eigen::MatrixXd stack(const Eigen::MatrixXd& obs, const Eigen::MatrixXd& act) {
  Eigen::MatrixXd x(obs.rows() + act.rows(), obs.cols());
  x << obs, act;
  return x;
}

// Moves every target network away from its online network, so that tests can tell them apart.
void perturb_targets(TD3& td3) {
  Rng rng(99);
  auto jitter = [&rng](Eigen::VectorXf& p) {
    for (Eigen::Index k = 0; k < p.size(); ++k) p(k) += static_cast<float>(rng.uniform(-0.2, 0.2));
  };
  jitter(td3.actor_target().net().params());
  for (int i = 0; i < td3.critic_target().n_critics(); ++i)
    jitter(td3.critic_target().q(i).params());
}

}  // namespace

TEST_CASE("TD3 target smoothing noise is clipped, and zero without a clip", "[algos][td3]") {
  TD3::Config cfg = small_config();
  cfg.off_policy.batch_size = 250;
  cfg.target_policy_noise = 10.0;
  cfg.target_noise_clip = 0.5;
  TD3 wide(cfg, small_setup());
  wide.train_on_batch(random_batch(250, 1), 0.0f);
  CHECK(wide.last_smoothing_noise().cwiseAbs().maxCoeff() == 0.5f);
  CHECK(wide.last_smoothing_noise().minCoeff() == -0.5f);
  cfg.target_policy_noise = 0.2;
  TD3 narrow(cfg, small_setup());
  narrow.train_on_batch(random_batch(250, 2), 0.0f);
  const Eigen::MatrixXf& noise = narrow.last_smoothing_noise();
  // N(0, 0.2) barely touched by a 2.5-sigma clip.
  CHECK(std::sqrt(noise.squaredNorm() / noise.size()) == Approx(0.2).epsilon(0.1));
  cfg.target_policy_noise = 0.1;  // SB3 DDPG's setting
  cfg.target_noise_clip = 0.0;
  TD3 ddpg_like(cfg, small_setup());
  ddpg_like.train_on_batch(random_batch(250, 3), 0.0f);
  CHECK(ddpg_like.last_smoothing_noise().isZero(0.0f));
}

TEST_CASE("TD3 critic target matches an independent double-precision computation", "[algos][td3]") {
  for (const int n : {8, 40}) {  // 40: the batch is split over two cores
    for (const double noise_std : {0.0, 0.3}) {
      INFO("batch " << n << ", target_policy_noise " << noise_std);
      TD3::Config cfg = small_config();
      cfg.target_policy_noise = noise_std;
      cfg.target_noise_clip = 0.25;
      TD3 td3(cfg, small_setup());
      perturb_targets(td3);
      const ReplayBatch b = random_batch(n, 3);
      td3.train_on_batch(b, 0.0f);

      const Eigen::MatrixXd noise = td3.last_smoothing_noise().cast<double>();
      if (noise_std == 0.0) {
        CHECK(noise.isZero(0.0));
      } else {
        CHECK(noise.cwiseAbs().maxCoeff() <= 0.25);
        CHECK(noise.cwiseAbs().maxCoeff() > 0.0);
      }
      const Eigen::MatrixXd s2 = b.next_obs.cast<double>();
      const Mlp& mu = td3.actor_target().net();
      const Eigen::MatrixXd next_a =
          (test::mlp_forward(mu, test::params_of(mu), s2).array().tanh().matrix() + noise)
              .cwiseMax(-1.0)
              .cwiseMin(1.0);
      Eigen::RowVectorXd min_q = Eigen::RowVectorXd::Constant(n, 1e300);
      for (int i = 0; i < 2; ++i) {
        const Mlp& target = td3.critic_target().q(i).net();
        min_q =
            min_q.cwiseMin(test::mlp_forward(target, test::params_of(target), stack(s2, next_a)));
      }
      const Eigen::RowVectorXd y = b.rewards.cast<double>().array() +
                                   (1.0 - b.dones.cast<double>().array()) * 0.9 * min_q.array();
      REQUIRE(td3.last_critic_target().cols() == n);
      for (int j = 0; j < n; ++j)
        CHECK(td3.last_critic_target()(0, j) == Approx(y(j)).margin(1e-5));
    }
  }
}

TEST_CASE("TD3 critic loss gradient matches finite differences", "[algos][td3][gradcheck]") {
  for (const int n : {8, 40}) {
    INFO("batch " << n);
    TD3 td3(small_config(), small_setup());
    perturb_targets(td3);
    const ReplayBatch b = random_batch(n, 4);
    // Learning rate 0: the parameters stay where they were, the gradients in grads().
    const Td3StepStats stats = td3.train_on_batch(b, 0.0f);
    CHECK_FALSE(stats.actor_updated);
    const Eigen::RowVectorXd y = td3.last_critic_target().cast<double>();
    const Eigen::MatrixXd x = stack(b.obs.cast<double>(), b.actions.cast<double>());

    double expected_loss = 0.0;
    for (int i = 0; i < 2; ++i) {
      const SplitMlp& q = td3.critic().q(i);
      // Loss = sum_i mse(Q_i, y) with y fixed: only critic i's own term depends on its
      // parameters.
      auto mse = [&](const Eigen::VectorXd& p) {
        return (test::mlp_forward(q.net(), p, x) - y).squaredNorm() / n;
      };
      expected_loss += mse(test::params_of(q.net()));
      test::require_grad_close(q.grads().cast<double>(),
                               test::numeric_gradient(mse, test::params_of(q.net())));
    }
    CHECK(stats.critic_loss == Approx(expected_loss).epsilon(1e-5));
  }
}

TEST_CASE("TD3 actor loss gradient runs through critic 1 into the actor only",
          "[algos][td3][gradcheck]") {
  for (const int n : {8, 40}) {
    INFO("batch " << n);
    TD3::Config cfg = small_config();
    cfg.policy_delay = 1;
    TD3 td3(cfg, small_setup());
    cfg.policy_delay = 2;
    TD3 critics_only(cfg, small_setup());
    const ReplayBatch b = random_batch(n, 5);
    const Td3StepStats stats = td3.train_on_batch(b, 0.0f);
    REQUIRE(stats.actor_updated);
    const Eigen::MatrixXd s = b.obs.cast<double>();
    const Mlp& q1 = td3.critic().q(0).net();
    auto actor_loss = [&](const Eigen::VectorXd& p) {
      const Eigen::MatrixXd a = test::mlp_forward(td3.actor().net(), p, s).array().tanh().matrix();
      return -test::mlp_forward(q1, test::params_of(q1), stack(s, a)).mean();
    };
    CHECK(stats.actor_loss == Approx(actor_loss(test::params_of(td3.actor().net()))).epsilon(1e-5));
    test::require_grad_close(
        td3.actor().net().grads().cast<double>(),
        test::numeric_gradient(actor_loss, test::params_of(td3.actor().net())));
    // The actor loss adds nothing to the critics' gradients (SB3's critic optimizer zeroes
    // what its backward leaves there).
    critics_only.train_on_batch(b, 0.0f);
    for (int i = 0; i < 2; ++i)
      CHECK(td3.critic().q(i).grads() == critics_only.critic().q(i).grads());
  }
}

TEST_CASE("TD3 updates the actor and the targets only every policy_delay-th step", "[algos][td3]") {
  TD3 td3(small_config(), small_setup());
  perturb_targets(td3);
  const ReplayBatch b = random_batch(40, 6);
  const float tau = 0.1f;
  for (int step = 1; step <= 4; ++step) {
    INFO("step " << step);
    const Eigen::VectorXf actor = td3.actor().net().params();
    const Eigen::VectorXf actor_target = td3.actor_target().net().params();
    std::vector<Eigen::VectorXf> q, q_target;
    for (int i = 0; i < 2; ++i) {
      q.push_back(td3.critic().q(i).params());
      q_target.push_back(td3.critic_target().q(i).params());
    }
    const Td3StepStats stats = td3.train_on_batch(b, 1e-3f);
    CHECK(td3.n_updates() == step);
    const bool delayed = step % 2 == 0;
    CHECK(stats.actor_updated == delayed);
    for (int i = 0; i < 2; ++i) {
      const Eigen::VectorXf& online = td3.critic().q(i).params();
      const Eigen::VectorXf& target = td3.critic_target().q(i).params();
      CHECK(online != q[i]);  // the critics learn every step
      if (delayed) {
        const Eigen::VectorXf expected = (1.0f - tau) * q_target[i] + tau * online;
        CHECK((target - expected).cwiseAbs().maxCoeff() < 1e-6f);
      } else {
        CHECK(target == q_target[i]);
      }
    }
    if (delayed) {
      CHECK(td3.actor().net().params() != actor);
      const Eigen::VectorXf expected =
          (1.0f - tau) * actor_target + tau * td3.actor().net().params();
      CHECK((td3.actor_target().net().params() - expected).cwiseAbs().maxCoeff() < 1e-6f);
    } else {
      CHECK(td3.actor().net().params() == actor);
      CHECK(td3.actor_target().net().params() == actor_target);
    }
  }
}

TEST_CASE("TD3 and DDPG defaults are SB3's", "[algos][td3]") {
  const TD3::Config t;
  CHECK(t.learning_rate(1.0) == 1e-3);
  CHECK(t.off_policy.buffer_size == 1000000);
  CHECK(t.off_policy.learning_starts == 100);
  CHECK(t.off_policy.batch_size == 256);
  CHECK(t.off_policy.tau == 0.005);
  CHECK(t.off_policy.gamma == 0.99);
  CHECK(t.off_policy.train_freq.frequency == 1);
  CHECK_FALSE(t.off_policy.train_freq.episodes);
  CHECK(t.off_policy.gradient_steps == 1);
  CHECK(t.action_noise.noise_type.empty());
  CHECK(t.policy_delay == 2);
  CHECK(t.target_policy_noise == 0.2);
  CHECK(t.target_noise_clip == 0.5);
  CHECK(t.policy.n_critics == 2);
  CHECK(t.policy.net_arch.pi == std::vector<int>{400, 300});
  CHECK(t.policy.net_arch.qf == std::vector<int>{400, 300});
  CHECK(t.policy.activation_fn == Activation::kReLU);

  const DDPG::Config d;
  const TD3::Config dt = DDPG::to_td3(d);
  CHECK(dt.learning_rate(1.0) == 1e-3);
  CHECK(dt.off_policy.buffer_size == 1000000);
  CHECK(dt.off_policy.learning_starts == 100);
  CHECK(dt.off_policy.batch_size == 256);
  CHECK(dt.off_policy.tau == 0.005);
  CHECK(dt.off_policy.gamma == 0.99);
  CHECK(dt.off_policy.train_freq.frequency == 1);
  CHECK(dt.off_policy.gradient_steps == 1);
  CHECK(dt.policy.net_arch.pi == std::vector<int>{400, 300});
  CHECK(dt.policy.net_arch.qf == std::vector<int>{400, 300});
  CHECK(dt.policy_delay == 1);
  CHECK(dt.target_noise_clip == 0.0);
  CHECK(dt.policy.n_critics == 1);
}

TEST_CASE("DDPG is TD3 with one critic, no smoothing and no delay", "[algos][td3][ddpg]") {
  DDPG::Config cfg;
  cfg.policy.net_arch = {{6, 5}, {6, 5}};
  cfg.off_policy.batch_size = 8;
  cfg.off_policy.tau = 0.1;
  DDPG ddpg(cfg, small_setup());
  TD3 twin(DDPG::to_td3(cfg), small_setup());
  CHECK(ddpg.id() == "DDPG");
  REQUIRE(ddpg.td3().critic().n_critics() == 1);
  const ReplayBatch b = random_batch(8, 8);
  for (int step = 1; step <= 3; ++step) {
    const Eigen::VectorXf actor = ddpg.td3().actor().net().params();
    const Eigen::VectorXf target = ddpg.td3().actor_target().net().params();
    const Td3StepStats s = ddpg.td3().train_on_batch(b, 1e-3f);
    twin.train_on_batch(b, 1e-3f);
    CHECK(s.actor_updated);  // every step
    CHECK(ddpg.td3().actor().net().params() != actor);
    CHECK(ddpg.td3().actor_target().net().params() != target);
    CHECK(ddpg.td3().last_smoothing_noise().isZero(0.0f));
  }
  TensorMap a, t;
  ddpg.save(a);
  twin.save(t);
  CHECK(a.count("critic.qf0.0.weight") == 1);
  CHECK(a.count("critic.qf1.0.weight") == 0);
  REQUIRE(a.size() == t.size());
  for (const auto& [name, tensor] : a) CHECK(tensor.bytes == t.at(name).bytes);
}

TEST_CASE("TD3 acts in the Box, saves under SB3 names and loads back", "[algos][td3]") {
  TD3::Config cfg = small_config();
  cfg.action_noise.noise_type = "normal";
  cfg.action_noise.noise_std = 0.5;
  TD3 td3(cfg, small_setup());
  const Eigen::MatrixXf obs = Eigen::MatrixXf::Random(kObsDim, 1);
  Eigen::MatrixXf env_a, buf_a;
  for (bool warmup : {true, false}) {
    for (int k = 0; k < 50; ++k) {
      td3.select_actions(obs, warmup, env_a, buf_a);
      CHECK(buf_a.cwiseAbs().maxCoeff() <= 1.0f);
      CHECK(env_a(0, 0) == Approx(2.0f * buf_a(0, 0)).margin(1e-6));           // Box(-2, 2)
      CHECK(env_a(1, 0) == Approx(0.5f * (buf_a(1, 0) + 1.0f)).margin(1e-6));  // Box(0, 1)
    }
  }
  // predict is actor(obs) unscaled, without noise, deterministic or not.
  Eigen::MatrixXf p1, p2;
  const Eigen::MatrixXf batch = Eigen::MatrixXf::Random(kObsDim, 5);
  td3.predict(batch, true, p1);
  td3.predict(batch, false, p2);
  CHECK(p1 == p2);
  const Eigen::MatrixXf mu = td3.actor().net().forward(batch).array().tanh().matrix();
  CHECK(p1(0, 3) == Approx(2.0f * mu(0, 3)).margin(1e-6));

  td3.train_on_batch(random_batch(8, 9), 1e-3f);
  td3.train_on_batch(random_batch(8, 10), 1e-3f);
  TensorMap tensors;
  td3.save(tensors);
  for (const char* name : {"actor.mu.0.weight", "actor.mu.2.bias", "actor.mu.4.weight",
                           "actor_target.mu.4.bias", "critic.qf0.0.weight", "critic.qf1.4.weight",
                           "critic_target.qf0.2.bias", "critic_target.qf1.4.bias"})
    CHECK(tensors.count(name) == 1);
  CHECK(tensors.size() == 6 * 6);  // actor, critics and targets: 6 networks x 3 layers x 2
  CHECK(tensors.at("critic.qf0.0.weight").shape == std::vector<int64_t>{6, kObsDim + kActDim});
  CHECK(tensors.at("actor.mu.4.weight").shape == std::vector<int64_t>{kActDim, 5});
  TD3 loaded(cfg, small_setup(555));
  loaded.load(tensors);
  Eigen::MatrixXf p3;
  td3.predict(batch, true, p1);
  loaded.predict(batch, true, p3);
  CHECK(p1 == p3);
}

TEST_CASE("TD3 training is deterministic for a seed", "[algos][td3]") {
  auto run = [] {
    const Registry& registry = builtin_registry();
    const std::string yaml =
        "env: {id: Pendulum-v1}\n"
        "algo: {id: TD3, learning_starts: 100, batch_size: 64, noise_type: normal,"
        " policy: {net_arch: [32, 32]}}\n";
    const Experiment e = parse_experiment(ConfigNode::load_string(yaml, "det.yaml"), registry);
    VecEnv env = make_vec_env(e.env, registry, 1, "");
    env.seed(3);
    auto algo = registry.find_algorithm("TD3")->make(
        e.algo.params, AlgorithmSetup{env.observation_space(), env.action_space(), 1, 3});
    TrainingHooks hooks;
    algo->learn(env, 300, hooks);
    TensorMap t;
    algo->save(t);
    return t.at("critic.qf1.2.weight").bytes;
  };
  CHECK(run() == run());
}

TEST_CASE("TD3 and DDPG train via the registry on Pendulum and MountainCarContinuous",
          "[algos][td3][ddpg]") {
  const Registry& registry = builtin_registry();
  testing::TempDir dir("td3_smoke");
  for (const char* algo : {"TD3", "DDPG"}) {
    for (const char* env_id : {"Pendulum-v1", "MountainCarContinuous-v0"}) {
      const std::string yaml =
          std::string("run: {name: smoke, seed: 2, total_timesteps: 400, out_dir: ") + dir.str() +
          ", console_interval: 1000}\n"
          "env: {id: " +
          env_id +
          ", n_envs: 2}\n"
          "algo: {id: " +
          algo +
          ", learning_starts: 100, batch_size: 32,"
          " noise_type: ornstein-uhlenbeck, noise_std: 0.3,"
          " policy: {net_arch: [32, 32]}}\n";
      INFO(yaml);
      const Experiment experiment =
          parse_experiment(ConfigNode::load_string(yaml, "smoke.yaml"), registry);
      const TrainOutcome outcome =
          train_experiment(experiment, registry, testing::test_execution());
      CHECK(outcome.timesteps == 400);
      const ModelFile model = read_model(outcome.model_path);
      const Experiment stored = experiment_from_model(model, registry);
      EnvPtr env = make_env(stored.env, registry, "", 0.0);
      auto loaded = algorithm_from_model(model, stored, registry, env->observation_space(),
                                         env->action_space());
      CHECK(loaded->id() == algo);
      const EvalResult r = evaluate_policy(*loaded, *env, 1, true, 3);
      REQUIRE(r.returns.size() == 1);
      CHECK(std::isfinite(r.returns[0]));
    }
  }
}

namespace {

double parse_mean_reward(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("mean_reward = (-?[0-9.eE+-]+)")));
  return std::stod(m[1]);
}

// rl-zoo's budget and hyperparameters (configs/pendulum_<algo>.yaml) through the real CLI;
// returns how many of seeds 1-3 reach -200 in 10 deterministic evaluation episodes.
int pendulum_seeds_solved(const std::string& algo) {
  const std::string source = RLRUN_SOURCE_DIR;
  testing::TempDir dir("learning_" + algo);
  int solved = 0;
  for (int seed : {1, 2, 3}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto train =
        testing::run_rlrun("train " + source + "/configs/pendulum_" + algo + ".yaml --seed " +
                           std::to_string(seed) + " --set run.out_dir=" + dir.str());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    REQUIRE(train.exit_code == 0);
    const auto eval =
        testing::run_rlrun("eval --model " + dir.str() + "/pendulum_" + algo + "/seed" +
                           std::to_string(seed) + "/model.zip --episodes 10");
    const double mean = parse_mean_reward(eval.output);
    std::printf("%s Pendulum-v1 seed %d: %.1f s, eval %.1f\n", algo.c_str(), seed, wall, mean);
    if (mean >= -200.0) ++solved;
  }
  return solved;
}

}  // namespace

// About 1-2 minutes per seed at rl-zoo's size (400x300 networks, 1e4 updates of batch 256).
// Not tagged [td3]: Catch2 runs hidden tests that a tag selects, and "[td3]" must stay quick.
// Run with `rlrun_tests "[td3_learning]"`.
TEST_CASE("learning: TD3 rl-zoo Pendulum config reaches -200 in 2 of 3 seeds",
          "[algos][learning][td3_learning][.slow]") {
  CHECK(pendulum_seeds_solved("td3") >= 2);
}

TEST_CASE("learning: DDPG rl-zoo Pendulum config reaches -200 in 2 of 3 seeds",
          "[algos][learning][td3_learning][.slow]") {
  CHECK(pendulum_seeds_solved("ddpg") >= 2);
}

// Throughput of train_on_batch at rl-zoo's Pendulum size; prints, asserts nothing (docs/benchmarks.md).
TEST_CASE("bench: TD3 gradient steps at rl-zoo Pendulum size", "[.td3_bench]") {
  for (const char* algo : {"TD3", "DDPG"}) {
    TD3::Config cfg;  // 400x300, batch 256
    if (std::string(algo) == "DDPG") cfg = DDPG::to_td3(DDPG::Config{});
    const AlgorithmSetup setup{Space::box(-8.0f, 8.0f, {3}), Space::box(-2.0f, 2.0f, {1}), 1, 1,
                               &testing::test_thread_pool()};
    TD3 td3(cfg, setup, algo);
    ReplayBatch b;
    b.obs = Eigen::MatrixXf::Random(3, 256);
    b.next_obs = Eigen::MatrixXf::Random(3, 256);
    b.actions = Eigen::MatrixXf::Random(1, 256);
    b.rewards = Eigen::RowVectorXf::Random(256);
    b.dones = Eigen::RowVectorXf::Zero(256);
    for (int i = 0; i < 20; ++i) td3.train_on_batch(b, 1e-3f);
    const int steps = 400;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    for (int i = 0; i < steps; ++i) td3.train_on_batch(b, 1e-3f);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // FLOPs per sample: 2 in out per layer forward, twice that backward (one fwd-equivalent
    // for the first layer's backward without input gradient would be exact; counted as 2).
    const double fwd = 2.0 * (4 * 400 + 400 * 300 + 300);
    const int n_critics = cfg.policy.n_critics;
    // Per step: actor target fwd, n target critics fwd, n critics fwd+bwd; per actor update:
    // actor fwd+bwd (3), critic 1 fwd + input-only bwd (2).
    const double per_step = fwd * (1 + n_critics + 3 * n_critics + 5.0 / cfg.policy_delay) * 256;
    // Wall time is what a run takes; process CPU time (both threads) is steadier on a shared
    // machine.
    std::printf(
        "%s (%d threads) train_on_batch: %.0f us/step wall, %.0f us CPU, %.1f GFLOP/s "
        "wall (%.0f%% of one core's 102), %.1f GFLOP/s per CPU-s (%.3f GFLOP/step)\n",
        algo, testing::test_thread_pool().threads(), s / steps * 1e6, cpu / steps * 1e6,
        per_step * steps / s * 1e-9, per_step * steps / s * 1e-9 / 102 * 100,
        per_step * steps / cpu * 1e-9, per_step * 1e-9);
  }
}
