// Search spaces: a study file's parameters (types, log, step, conditions, list-valued choices)
// and rl-zoo's spaces per algorithm, whose every sample must be a valid override of a matching
// shipped experiment (a key rlrun does not know would fail every trial).
#include <catch2/catch.hpp>

#include <filesystem>
#include <random>

#include "rlrun/core/errors.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/tune/random_sampler.hpp"
#include "rlrun/tune/search_space.hpp"
#include "rlrun/tune/study_config.hpp"
#include "rlrun/tune/zoo_spaces.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::tune;
using json = nlohmann::json;

namespace {

// Answers suggest() with uniform draws (the random sampler's) and records what was asked.
class RandomSuggest : public TrialSuggest {
 public:
  explicit RandomSuggest(uint64_t seed) : rng_(seed) {}
  json suggest(const std::string& name, const Distribution& d) override {
    asked.push_back(name);
    const double internal = sample_uniform(rng_, d);
    REQUIRE(contains(d, internal));
    params[name] = to_external(d, internal);
    return params[name];
  }
  void set_user_attr(const std::string& key, const json& value) override {
    user_attrs[key] = value;
  }
  std::vector<std::string> asked;
  json params = json::object();
  json user_attrs = json::object();

 private:
  Rng rng_;
};

// Answers with fixed values.
class ScriptedSuggest : public TrialSuggest {
 public:
  explicit ScriptedSuggest(json values) : values_(std::move(values)) {}
  json suggest(const std::string& name, const Distribution&) override {
    asked.push_back(name);
    return values_.at(name);
  }
  void set_user_attr(const std::string&, const json&) override {}
  std::vector<std::string> asked;

 private:
  json values_;
};

std::unique_ptr<StudySpace> space_of(const std::string& yaml) {
  return parse_space(ConfigNode::load_string(yaml, "study.yaml").child("space"), "PPO", false);
}

std::vector<std::string> assignments(const std::vector<Override>& overrides) {
  std::vector<std::string> out;
  for (const auto& o : overrides) out.push_back(o.assignment());
  return out;
}

std::string config(const std::string& name) {
  return std::string(RLRUN_SOURCE_DIR) + "/configs/" + name;
}

}  // namespace

TEST_CASE("search space: a study file's parameters, conditions and list-valued choices", "[tune]") {
  auto space = space_of(
      "space:\n"
      "  algo.learning_rate: {float: [1.0e-5, 1.0e-2], log: true}\n"
      "  algo.n_epochs: {int: [1, 20], step: 2}\n"
      "  algo.policy.net_arch: {categorical: [[64], [64, 64]]}\n"
      "  algo.policy.activation_fn: {categorical: [tanh, relu]}\n"
      "  algo.ent_coef: {float: [0.0, 0.1], step: 0.01, if: {algo.policy.activation_fn: relu}}\n");
  ScriptedSuggest tanh({{"algo.learning_rate", 3e-4},
                        {"algo.n_epochs", 5},
                        {"algo.policy.net_arch", "[64, 64]"},
                        {"algo.policy.activation_fn", "tanh"},
                        {"algo.ent_coef", 0.02}});
  const auto overrides = space->sample(tanh);
  CHECK(tanh.asked.size() == 4);  // the condition did not hold: ent_coef is not asked
  CHECK(assignments(overrides) ==
        std::vector<std::string>{"algo.learning_rate=0.00029999999999999997", "algo.n_epochs=5",
                                 "algo.policy.net_arch=[64, 64]",
                                 "algo.policy.activation_fn=\"tanh\""});
  Registry registry = make_builtin_registry();
  const Experiment e =
      load_experiment(config("cartpole_ppo.yaml"), assignments(overrides), registry);
  CHECK(e.resolved["algo"]["n_epochs"].as<int>() == 5);
  CHECK(e.resolved["algo"]["policy"]["net_arch"].size() == 2);

  ScriptedSuggest relu({{"algo.learning_rate", 1e-3},
                        {"algo.n_epochs", 1},
                        {"algo.policy.net_arch", "[64]"},
                        {"algo.policy.activation_fn", "relu"},
                        {"algo.ent_coef", 0.02}});
  CHECK(space->sample(relu).size() == 5);
  // Random draws stay inside their distributions (RandomSuggest checks), for many seeds.
  for (uint64_t seed = 0; seed < 50; ++seed) {
    RandomSuggest random(seed);
    for (const auto& o : space->sample(random)) CHECK_FALSE(o.yaml.empty());
  }
  // overrides_for: a finished trial's parameters give the same overrides.
  CHECK(assignments(space->overrides_for({{"algo.learning_rate", 3e-4},
                                          {"algo.n_epochs", 5},
                                          {"algo.policy.net_arch", "[64, 64]"},
                                          {"algo.policy.activation_fn", "tanh"}})) ==
        assignments(overrides));
}

TEST_CASE("search space: bad parameters are errors at their line", "[tune]") {
  const auto error = [](const std::string& yaml) -> std::string {
    try {
      space_of(yaml);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  CHECK_THAT(error("space:\n  a: {float: [1, 2], lgo: true}\n"),
             Catch::Contains("study.yaml:2") && Catch::Contains("did you mean 'log'"));
  CHECK_THAT(error("space:\n  a: {float: [2, 1]}\n"), Catch::Contains("low must be <= high"));
  CHECK_THAT(error("space:\n  a: {float: [0, 1], log: true}\n"), Catch::Contains("low > 0"));
  CHECK_THAT(error("space:\n  a: {int: [1, 4], float: [0, 1]}\n"), Catch::Contains("exactly one"));
  CHECK_THAT(error("space:\n  a: {categorical: []}\n"), Catch::Contains("non-empty"));
  CHECK_THAT(error("space:\n  a: {int: [1, 4], if: {b: 1}}\n"),
             Catch::Contains("'b' is not a parameter listed before"));
  CHECK_THAT(error("space: zoo\n").empty() ? std::string("ok") : error("space: zoo\n"),
             Catch::Contains("ok"));
  CHECK_THAT(error("space: grid\n"), Catch::Contains("zoo or a map"));
  try {
    // rl-zoo's hyperparams_opt.py has no sampler for CrossQ.
    parse_space(ConfigNode::load_string("space: zoo\n", "study.yaml").child("space"), "CrossQ",
                false);
    FAIL("CrossQ has no zoo space in rlrun");
  } catch (const ConfigError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("no search space for CrossQ"));
  }
}

TEST_CASE("search space: rl-zoo's spaces give valid overrides of the shipped configs", "[tune]") {
  Registry registry = make_builtin_registry();
  const std::vector<std::tuple<std::string, std::string, bool>> cases{
      {"PPO", "cartpole_ppo.yaml", false},
      {"A2C", "cartpole_a2c.yaml", false},
      {"DQN", "cartpole_dqn.yaml", false},
      {"SAC", "pendulum_sac.yaml", false},
      {"TD3", "pendulum_td3.yaml", false},
      {"DDPG", "pendulum_ddpg.yaml", false},
      {"TQC", "pendulum_tqc.yaml", false},
      {"DQN", "bitflipping_dqn_her.yaml", true},
      {"SAC", "gripper_reach_sac_her.yaml", true},
      {"QRDQN", "cartpole_qrdqn.yaml", false},
      {"TRPO", "zoo/pendulum_trpo.yaml", false},
      {"ARS", "zoo/pendulum_ars.yaml", false},
      {"RecurrentPPO", "cartpole_novel_recurrent_ppo.yaml", false}};
  for (const auto& [algo, file, her] : cases) {
    INFO(algo << " " << file);
    auto space = zoo_space(algo, her);
    for (uint64_t seed = 0; seed < 8; ++seed) {
      RandomSuggest trial(seed);
      const auto overrides = space->sample(trial);
      INFO(trial.params.dump());
      try {
        load_experiment(config(file), assignments(overrides), registry);
      } catch (const ConfigError& e) {
        // A combination rlrun refuses (as SB3 would) is a failed trial; a key rlrun does not
        // know would fail them all.
        CHECK_THAT(std::string(e.what()), !Catch::Contains("unknown key"));
      }
      if (her) CHECK(trial.params.contains("goal_selection_strategy"));
      // The space is the zoo's: the names Optuna shows are the zoo's.
      if (algo == "PPO" || algo == "RecurrentPPO") {
        CHECK(trial.asked == std::vector<std::string>{
                                 "batch_size", "n_steps", "one_minus_gamma", "one_minus_gae_lambda",
                                 "learning_rate", "ent_coef", "clip_range", "n_epochs",
                                 "max_grad_norm", "net_arch", "activation_fn"});
        CHECK(trial.user_attrs["gamma"].get<double>() ==
              Approx(1 - trial.params["one_minus_gamma"].get<double>()));
      }
      if (algo == "QRDQN") CHECK(trial.asked.back() == "n_quantiles");  // after DQN's space
      if (algo == "ARS")
        CHECK(trial.asked == std::vector<std::string>{"n_delta_pow", "learning_rate", "delta_std",
                                                      "top_frac_size"});
      if (algo == "TRPO")
        CHECK(trial.user_attrs["n_steps"].get<int64_t>() ==
              int64_t{1} << trial.params["n_steps_pow"].get<int64_t>());
      if (algo == "TQC")
        CHECK(trial.params["top_quantiles_to_drop_per_net"].get<int>() <
              trial.params["n_quantiles"].get<int>());
    }
  }
}

TEST_CASE("distributions: Optuna's JSON form and its checks", "[tune]") {
  const auto f = make_float_distribution("x", 0.1, 1.0, false, 0.1);
  CHECK(f.high == 1.0);  // a whole number of steps in decimal, as Optuna's Decimal arithmetic
  CHECK(make_float_distribution("x", 0.0, 1.0, false, 0.3).high == Approx(0.9));
  CHECK(make_int_distribution("n", 1, 10, false, 4).high == 9);
  CHECK(
      distribution_to_json(f) ==
      R"({"name":"FloatDistribution","attributes":{"step":0.1,"low":0.1,"high":1.0,"log":false}})");
  const auto back = distribution_from_json(distribution_to_json(f), "here");
  CHECK(std::get<FloatDistribution>(back) == f);
  const auto c =
      distribution_from_json(R"({"type": "categorical", "choices": ["a", null, 2]})", "here");
  CHECK(to_external(c, 1).is_null());
  CHECK(to_internal(c, 2.0) == 2);  // 2 == 2.0, as Python compares
  CHECK_THROWS_AS(to_internal(c, "b"), ConfigError);
  CHECK_THROWS_AS(distribution_from_json(
                      R"({"name": "FloatDistribution", "attributes": {"low": "x"}})", "here"),
                  ConfigError);
  CHECK_THROWS_AS(distribution_from_json(R"({"name": "Evil", "attributes": {}})", "here"),
                  ConfigError);
  CHECK(single(make_int_distribution("n", 3, 4, false, 2)));
  CHECK_FALSE(contains(make_int_distribution("n", 1, 9, false, 2), 4));
}

TEST_CASE("study files: every shipped one under configs/tune loads", "[tune]") {
  Registry registry = make_builtin_registry();
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(config("tune"))) {
    INFO(entry.path());
    const StudyConfig study = load_study(entry.path().string(), registry);
    CHECK(study.n_trials > 0);
    CHECK_FALSE(study.space->describe().empty());
    ++n;
  }
  CHECK(n >= 1);
}
