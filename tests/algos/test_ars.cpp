// ARS (src/rlrun/algos/ars/): the update from the candidates' returns against a hand
// computation (top directions, unbiased std, step size), the policy's actions (tanh then scaled,
// or clipped; argmax for Discrete), the LinearPolicy's missing biases and zero start, the env
// steps counted as sb3-contrib counts them through evaluate_policy's callback, sb3-contrib's
// defaults, and a short run through the registry. The learning bar is hidden ([.slow]).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "algos/zoo_learning_bar.hpp"
#include "fakes/constant_env.hpp"
#include "rlrun/algos/ars/ars.hpp"
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

namespace {

ARS::Config linear_config(int n_delta, int n_top) {
  ARS::Config c;
  c.n_delta = n_delta;
  c.n_top = n_top;
  c.policy.net_arch = {};
  c.policy.with_bias = false;
  c.policy.squash_output = false;
  return c;
}

TrainOutcome train_yaml(const std::string& yaml, const std::string& name) {
  const Experiment e =
      parse_experiment(ConfigNode::load_string(yaml, name + ".yaml"), builtin_registry());
  return train_experiment(e, builtin_registry(), testing::test_execution());
}

}  // namespace

TEST_CASE("ARS's defaults are sb3-contrib 2.4's", "[algos][ars]") {
  const ARS::Config c;
  CHECK(c.n_delta == 8);
  CHECK(!c.n_top);
  CHECK(c.learning_rate(1.0) == Approx(0.02));
  CHECK(c.delta_std(1.0) == Approx(0.05));
  CHECK(c.zero_policy);
  CHECK(c.alive_bonus_offset == 0.0);
  CHECK(c.n_eval_episodes == 1);
  CHECK(c.policy.net_arch == std::vector<int>{64, 64});
  CHECK(c.policy.activation_fn == Activation::kReLU);
  CHECK(c.policy.with_bias);
  CHECK(c.policy.squash_output);
}

TEST_CASE("ARS steps along the best directions' return differences", "[algos][ars]") {
  // A linear policy without bias on 2 observations and 1 action: 2 parameters, zero at start.
  ARS ars(linear_config(3, 2),
          AlgorithmSetup{Space::box(-1.0f, 1.0f, {2}), Space::box(-1.0f, 1.0f, {1}), 1, 0});
  REQUIRE(ars.weights().size() == 2);
  CHECK(ars.weights().isZero());
  Eigen::MatrixXf deltas(3, 2);
  deltas << 1, 2, -1, 0.5, 3, -2;
  Eigen::VectorXd returns(6);
  returns << 10, 4, 7,  // plus candidates
      2, 9, 1;          // minus candidates
  // max(plus, minus) = 10, 9, 7: directions 0 and 1 are the top two.
  double return_std = 0;
  const double step_size = ars.apply_update(returns, deltas, 0.5, return_std);
  const double mean = (10 + 4 + 2 + 9) / 4.0;
  const double std = std::sqrt(((10 - mean) * (10 - mean) + (4 - mean) * (4 - mean) +
                                (2 - mean) * (2 - mean) + (9 - mean) * (9 - mean)) /
                               3.0);
  CHECK(return_std == Approx(std));
  CHECK(step_size == Approx(0.5 / (2 * std + 1e-6)));
  // (10 - 2) d0 + (4 - 9) d1 = (8 + 5, 16 - 2.5)
  CHECK(ars.weights()(0) == Approx(step_size * 13.0));
  CHECK(ars.weights()(1) == Approx(step_size * 13.5));
}

TEST_CASE("ARS acts as ARSPolicy: tanh and scale, clip, or argmax", "[algos][ars]") {
  const AlgorithmSetup box{Space::box(-1.0f, 1.0f, {2}), Space::box(-2.0f, 4.0f, {1}), 1, 0};
  Eigen::MatrixXf obs(2, 2);
  obs << 1, -1, 2, 0.5;
  Eigen::MatrixXf actions;
  SECTION("squash_output: low + (tanh(x) + 1) (high - low) / 2") {
    ARS::Config c = linear_config(1, 1);
    c.policy.squash_output = true;
    ARS ars(c, box);
    ars.set_weights(Eigen::Vector2f(0.5f, -0.25f));
    ars.predict(obs, true, actions);
    CHECK(actions(0, 0) == Approx(-2 + (std::tanh(0.0) + 1) * 3));
    CHECK(actions(0, 1) == Approx(-2 + (std::tanh(-0.625) + 1) * 3));
  }
  SECTION("LinearPolicy: clipped to the bounds") {
    ARS ars(linear_config(1, 1), box);
    ars.set_weights(Eigen::Vector2f(5.0f, 0.0f));
    ars.predict(obs, true, actions);
    CHECK(actions(0, 0) == 4.0f);
    CHECK(actions(0, 1) == -2.0f);
  }
  SECTION("Discrete: argmax of the outputs") {
    ARS ars(linear_config(1, 1),
            AlgorithmSetup{Space::box(-1.0f, 1.0f, {2}), Space::discrete(3, 1), 1, 0});
    Eigen::VectorXf w = Eigen::VectorXf::Zero(6);
    w(2) = 1.0f;  // weight (out x in) column-major: output 2 reads observation 0
    ars.set_weights(w);
    ars.predict(obs, true, actions);
    CHECK(actions(0, 0) == 3.0f);  // start 1 + index 2
    CHECK(actions(0, 1) == 1.0f);  // all zero but -1 for output 2: argmax 0
  }
}

TEST_CASE("ARS evaluates candidates on a copy: callbacks during an update see the weights",
          "[algos][ars]") {
  // sb3-contrib evaluates each candidate with train_policy, a deep copy; an EvalCallback that
  // runs between two steps evaluates model.policy, the unperturbed weights.
  ARS::Config c;
  c.n_delta = 2;
  c.zero_policy = false;
  c.policy.net_arch = {4};
  ARS ars(c, AlgorithmSetup{Space::box(-1.0f, 1.0f, {1}), Space::discrete(2), 1, 0});
  std::vector<EnvPtr> envs;
  envs.push_back(std::make_unique<fakes::ConstantEnv>(false, 5));
  VecEnv env(std::move(envs));
  const Eigen::VectorXf before = ars.weights();
  int checked = 0;
  TrainingHooks hooks;
  hooks.on_step = [&](int64_t) {
    CHECK(ars.weights() == before);  // the update has not been applied yet
    ++checked;
    return true;
  };
  ars.learn(env, 20, hooks);  // one update: 4 candidates x 5 steps
  CHECK(checked == 20);
}

TEST_CASE("ARS counts env steps as evaluate_policy's callback does", "[algos][ars]") {
  testing::TempDir dir("ars_steps");
  // IdentityEnv-v0's episodes last 100 steps. n_envs 2, n_eval_episodes 3: targets 1 and 2
  // episodes; 100 steps with both envs counting (2 x 2 each), then 100 with one (2 each):
  // 600 per candidate, 4 candidates, 2400 per update.
  const TrainOutcome outcome =
      train_yaml("run: {name: ars_steps, seed: 1, total_timesteps: 2400, out_dir: " + dir.str() +
                     ", console_interval: 1000000}\n"
                     "env: {id: IdentityEnv-v0, n_envs: 2}\n"
                     "algo: {id: ARS, n_delta: 2, n_eval_episodes: 3, policy: {net_arch: [8]}}\n",
                 "ars_steps");
  CHECK(outcome.timesteps == 2400);
  const ModelFile model = read_model(outcome.model_path);
  CHECK(model.meta.algorithm == "ARS");
  CHECK(model.tensors.at("action_net.0.weight").shape == std::vector<int64_t>{8, 4});
  CHECK(model.tensors.count("action_net.2.bias") == 1);
}

TEST_CASE("ARS trains CartPole's LinearPolicy through the registry, deterministically",
          "[algos][ars]") {
  testing::TempDir dir("ars_cartpole");
  const auto run = [&](const std::string& name) {
    const TrainOutcome outcome = train_yaml(
        "run: {name: " + name + ", seed: 3, total_timesteps: 5000, out_dir: " + dir.str() +
            ", console_interval: 1000000}\n"
            "env: {id: CartPole-v1}\n"
            "algo: {id: ARS, n_delta: 2, policy: {net_arch: [], with_bias: false, "
            "squash_output: false}}\n",
        name);
    return read_model(outcome.model_path);
  };
  const ModelFile a = run("a"), b = run("b");
  CHECK(a.tensors.count("action_net.0.bias") == 0);  // LinearPolicy: no bias
  CHECK(a.tensors.at("action_net.0.weight").bytes == b.tensors.at("action_net.0.weight").bytes);
  const Experiment stored = experiment_from_model(a, builtin_registry());
  EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
  auto loaded = algorithm_from_model(a, stored, builtin_registry(), env->observation_space(),
                                     env->action_space());
  CHECK(evaluate_policy(*loaded, *env, 2, true, 5).returns.size() == 2);
}

TEST_CASE("ARS reaches the zoo's CartPole-v1 and MountainCarContinuous-v0 scores in seeds 1-3",
          "[.slow][algos][ars_slow]") {
  testing::check_zoo_learning_bar("configs/zoo/cartpole_ars.yaml", 475.0);
  testing::check_zoo_learning_bar("configs/zoo/mountaincarcontinuous_ars.yaml", 90.0);
}
