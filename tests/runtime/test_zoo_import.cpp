// The rl-zoo importer (runtime/zoo/): every entry of the zoo's hyperparameter files for
// rlrun's envs (tests/data/zoo/, copies of hyperparams/<algo>.yml at four zoo versions)
// imports without a hand edit and trains; what it cannot translate is an error at the zoo
// file's line and column.
#include <algorithm>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/runtime/workflows/zoo/experiment_text.hpp"
#include "rlrun/runtime/workflows/zoo/python_literal.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;
using namespace rlrun::zoo;
using rlrun::testing::TempDir;

namespace {

const std::string kZooData = std::string(RLRUN_SOURCE_DIR) + "/tests/data/zoo";
const std::vector<std::string> kAlgos{"ppo", "a2c", "dqn", "sac", "td3", "ddpg"};
const std::vector<std::string> kVersions{"", "2023-04", "2021-02", "2020-12"};

// The files of a zoo version: sb3-contrib's TQC, QR-DQN, TRPO, ARS, CrossQ and RecurrentPPO
// (tqc.yml, qrdqn.yml, trpo.yml, ars.yml, crossq.yml, ppo_lstm.yml) are kept for the current
// one only.
std::vector<std::string> algos_of(const std::string& version) {
  std::vector<std::string> algos = kAlgos;
  if (version.empty()) {
    algos.push_back("tqc");
    algos.push_back("qrdqn");
    algos.push_back("trpo");
    algos.push_back("ars");
    algos.push_back("crossq");
    algos.push_back("ppo_lstm");
  }
  return algos;
}

// The env a `default` entry is tried on: one without an entry of its own.
std::string default_env(const std::string& algo) {
  return algo == "sac" || algo == "td3" || algo == "ddpg" || algo == "tqc" || algo == "crossq"
             ? "IdentityEnvBox-v0"
             : "IdentityEnv-v0";
}

bool off_policy(const std::string& algo) {
  return algo == "sac" || algo == "td3" || algo == "ddpg" || algo == "dqn" || algo == "tqc" ||
         algo == "qrdqn" || algo == "crossq";
}

// Imports `env` from `file` and checks the experiment; with `train`, trains it briefly: 2000
// steps (at least one rollout; RecurrentPPO's trained for one epoch), with learning_starts
// lowered to 1500 so that off-policy entries take (500) gradient steps (CrossQ's 10), and a
// replay buffer of at most 100000 transitions. Returns "" or the error.
std::string import_and_train(const std::string& file, const std::string& algo,
                             const std::string& env, const std::string& out_dir, bool train) {
  try {
    Registry registry = make_builtin_registry();
    std::vector<std::string> overrides{"run.total_timesteps=2000", "run.out_dir=" + out_dir,
                                       "eval.freq=0", "run.console_interval=1000"};
    // The entry as imported, to read the values the overrides bound.
    const ZooImport imported = translate_zoo_entry(read_zoo_entry(file, env, ""), registry);
    if (algo == "crossq") {
      // 10 gradient steps (3 of the actor): CrossQ's critics are 1024 to 2048 wide and pass
      // 2 x batch_size columns (MuJoCo's 2048-wide entries: ~0.4 s a step on 2 cores).
      overrides.push_back("algo.learning_starts=1990");
      overrides.push_back("algo.buffer_size=100000");
    } else if (algo == "ppo_lstm") {
      // One epoch of the first rollout: the LSTM's backpropagation through time over a whole
      // rollout (CarRacing's CnnLstmPolicy: 8 x 512 frames) is what costs (26 s for 10).
      overrides.push_back("algo.n_epochs=1");
    } else if (off_policy(algo)) {
      const YAML::Node a = imported.experiment["algo"];
      if (a["learning_starts"] && a["learning_starts"].as<double>() > 1500)
        overrides.push_back("algo.learning_starts=1500");
      if (!a["buffer_size"] || a["buffer_size"].as<double>() > 100000)
        overrides.push_back("algo.buffer_size=100000");
    }
    const Experiment experiment = load_zoo_experiment(file, env, "", overrides, registry);
    if (!train) return "";
    const TrainOutcome outcome = train_experiment(experiment, registry, testing::test_execution());
    if (!std::filesystem::exists(outcome.run_dir + "/model.zip")) return "no model.zip";
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::vector<std::string> entry_names(const std::string& file) {
  std::vector<std::string> names;
  const YAML::Node root = YAML::LoadFile(file);
  for (const auto& kv : root) names.push_back(kv.first.Scalar());
  return names;
}

std::string write_file(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::string import_error(const std::string& file, const std::string& env) {
  try {
    Registry registry = make_builtin_registry();
    load_zoo_experiment(file, env, "", {}, registry);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("Python literals: the zoo's subset is read, anything else refused",
          "[zoo][python_literal]") {
  const PyValue v = parse_python_literal(
      "dict(log_std_init=-2, ortho_init=False, activation_fn=nn.ReLU,\n"
      "     net_arch=dict(pi=[256, 256], vf=[256]), x={'a': None, 'b': 1e-3}, t=(1, 'episode'))");
  REQUIRE(v.kind == PyValue::Kind::kDict);
  CHECK(v.find("log_std_init")->number == -2.0);
  CHECK(v.find("log_std_init")->integral);
  CHECK_FALSE(v.find("ortho_init")->boolean);
  CHECK(v.find("activation_fn")->kind == PyValue::Kind::kName);
  CHECK(v.find("activation_fn")->text == "nn.ReLU");
  CHECK(v.find("net_arch")->find("pi")->items.size() == 2);
  CHECK(v.find("x")->find("a")->kind == PyValue::Kind::kNone);
  CHECK(v.find("x")->find("b")->number == 1e-3);
  CHECK(v.find("t")->items[1].text == "episode");
  auto refused = [](const std::string& text) {
    try {
      parse_python_literal(text);
    } catch (const PythonLiteralError& e) {
      return std::string(e.what()) + " @" + std::to_string(e.offset());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused("__import__('os').system('x')"),
             Catch::Contains("calls other than dict") && Catch::Contains("@0"));
  CHECK_THAT(refused("dict(a=open('f'))"),
             Catch::Contains("calls other than dict") && Catch::Contains("@7"));
  CHECK_THAT(refused("dict(a=[1][0])"), Catch::Contains("expected ','"));
  CHECK_THAT(refused("dict(a=1 + 2)"), Catch::Contains("expected ','"));
  CHECK_THAT(refused("dict(a=nn.ReLU())"), Catch::Contains("calls other than dict"));
  CHECK_THAT(refused("{'a': 1, 'a': 2}"), Catch::Contains("given twice"));
  CHECK_THAT(refused("lambda x: x"), Catch::Contains("unexpected"));
  CHECK_THAT(refused(std::string(100, '[')), Catch::Contains("nested too deeply"));
}

// Every entry of `versions`, imported and checked (train = false) or also trained.
// `only`: the algorithms to try (empty: all of the version's).
void check_every_entry(bool train, const std::vector<std::string>& versions = kVersions,
                       const std::vector<std::string>& only = {}) {
  TempDir dir(train ? "zoo_entries_train" : "zoo_entries");
  for (const std::string& version : versions) {
    for (const std::string& algo : algos_of(version)) {
      if (!only.empty() && std::find(only.begin(), only.end(), algo) == only.end()) continue;
      const std::string relative = (version.empty() ? "" : version + "/") + algo + ".yml";
      const std::string file = kZooData + "/" + relative;
      for (const std::string& name : entry_names(file)) {
        const std::string env = name == "default" ? default_env(algo) : name;
        const std::string key = relative + ":" + name;
        INFO(key);
        const std::string error = import_and_train(file, algo, env, dir.str(), train);
        if (algo == "ppo_lstm" && name == "default") {
          // ppo_lstm.yml's default names 'MlpPolicy', which sb3-contrib's RecurrentPPO does not
          // have (its policy_aliases are the *LstmPolicy ones): refused, as RecurrentPPO would.
          CHECK_THAT(error, Catch::Contains("MlpLstmPolicy"));
          continue;
        }
        CHECK(error == "");
      }
    }
  }
}

TEST_CASE("zoo import: every entry of the zoo's files for rlrun's envs imports", "[zoo]") {
  check_every_entry(false);
}

// The current zoo files' entries train 2000 steps each, in three test cases (ctest runs them
// side by side, and each stays well inside CI's per-test limit: together about 10 minutes on
// 2 cores with the MuJoCo and ppo_lstm entries, 2026-12-01). PPO and A2C collect a whole first
// rollout (up to 65536 steps for BipedalWalker's 32 envs x 2048), SAC/TD3/DDPG take a gradient
// step per env step after learning_starts.
const std::vector<std::vector<std::string>> kTrainingGroups = {
    {"a2c", "ppo", "trpo", "ars"},
    {"ppo_lstm", "dqn", "qrdqn"},
    {"sac", "td3", "ddpg", "tqc", "crossq"}};

TEST_CASE("zoo import: the training groups cover every algorithm of the current zoo files",
          "[zoo]") {
  std::set<std::string> grouped;
  for (const auto& group : kTrainingGroups) grouped.insert(group.begin(), group.end());
  const std::vector<std::string> algos = algos_of("");
  CHECK(grouped == std::set<std::string>(algos.begin(), algos.end()));
}

TEST_CASE("zoo import: every on-policy entry of the current zoo files trains 2000 steps",
          "[zoo][zoo_train]") {
  check_every_entry(true, {""}, kTrainingGroups[0]);
}

TEST_CASE("zoo import: every ppo_lstm and value-based entry of the current zoo files trains",
          "[zoo][zoo_train]") {
  check_every_entry(true, {""}, kTrainingGroups[1]);
}

TEST_CASE("zoo import: every off-policy actor-critic entry of the current zoo files trains",
          "[zoo][zoo_train]") {
  check_every_entry(true, {""}, kTrainingGroups[2]);
}

// Every version's entries: 7.6 minutes on a quiet 2-core machine (2026-11-26).
TEST_CASE("zoo import: every entry of every zoo version trains 2000 steps",
          "[.zoo_entries][slow]") {
  check_every_entry(true);
}

TEST_CASE("zoo import: the translation of a zoo entry", "[zoo]") {
  TempDir dir("zoo_translation");
  Registry registry = make_builtin_registry();
  const std::string file = write_file(dir, "a2c.yml", R"zoo(# a zoo file
CartPole-v1:
  normalize: "{'norm_obs': True, 'norm_reward': False, 'gamma': 0.9}"
  n_envs: 8
  n_timesteps: !!float 5e5
  policy: 'MlpPolicy'
  ent_coef: .0
  learning_rate: lin_7e-4
  policy_kwargs: "dict(net_arch=[dict(pi=[32], vf=[32])], activation_fn=nn.Tanh,
                       share_features_extractor=False)"
  env_wrapper:
    - gymnasium.wrappers.TimeLimit:
        max_episode_steps: 200
  callback:
    - stable_baselines3.common.callbacks.CheckpointCallback:
        save_freq: 1000
default:
  n_timesteps: 1000
  policy: 'MlpPolicy'
)zoo");
  const ZooImport imported = translate_zoo_entry(read_zoo_entry(file, "CartPole-v1", ""), registry);
  const YAML::Node& x = imported.experiment;
  CHECK(x["algo"]["id"].as<std::string>() == "A2C");
  CHECK(x["run"]["name"].as<std::string>() == "a2c_CartPole-v1");
  CHECK(x["run"]["total_timesteps"].as<double>() == 5e5);
  CHECK(x["env"]["n_envs"].as<int>() == 8);
  // gamma: the entry sets none, so the dict's own reaches VecNormalize.
  CHECK(x["env"]["normalize"]["norm_reward"].as<bool>() == false);
  CHECK(x["env"]["normalize"]["gamma"].as<double>() == 0.9);
  CHECK(x["env"]["max_episode_steps"].as<int>() == 200);
  CHECK(x["checkpoint"]["freq"].as<int>() == 8000);  // 1000 calls x 8 envs
  CHECK(x["algo"]["learning_rate"].as<std::string>() == "lin_7e-4");
  CHECK(x["algo"]["policy"]["activation_fn"].as<std::string>() == "tanh");
  CHECK(x["eval"]["freq"].as<int>() == 25000);
  CHECK(x["eval"]["n_episodes"].as<int>() == 5);
  // A2C's policy has share_features_extractor (it matters for a CNN; a flatten has nothing to
  // share), so it carries over rather than being noted.
  CHECK(imported.notes.empty());
  CHECK(x["algo"]["policy"]["share_features_extractor"].as<bool>() == false);
  // The written file carries its origin and is an experiment `rlrun train` reads.
  const std::string text = experiment_text(imported);
  CHECK_THAT(text, Catch::StartsWith("# Imported by `rlrun zoo import` (rlrun "));
  CHECK_THAT(text, Catch::Contains(file + ", entry 'CartPole-v1' (A2C)"));
  CHECK_THAT(text, !Catch::Contains("!!float"));
  // net_arch dicts need h/policy: the file is re-read here without the policy map.
  YAML::Node reread = YAML::Load(text);
  reread["algo"].remove("policy");
  const Experiment e = parse_experiment(ConfigNode::from_yaml(reread, "imported"), registry);
  CHECK(e.env.section.normalize.enabled);
  CHECK(e.env.normalize_gamma() == 0.9);
  CHECK(e.run.total_timesteps == 500000);

  // The entry's gamma wins over the dict's (rl-zoo overwrites normalize_kwargs["gamma"]), and
  // `gamma: null` says "the algorithm's".
  const std::string with_gamma = write_file(dir, "ppo.yml", R"(MountainCar-v0:
  normalize: true
  n_timesteps: 1000
  policy: 'MlpPolicy'
  gamma: 0.95
)");
  const Experiment m = load_zoo_experiment(with_gamma, "MountainCar-v0", "", {}, registry);
  CHECK(m.env.normalize_gamma() == 0.95);
  // v2 lander entries serve the v3 env; `default` serves an env without an entry.
  const std::string lander =
      write_file(dir, "dqn.yml", "LunarLander-v2:\n  n_timesteps: 1000\n  policy: 'MlpPolicy'\n");
  CHECK(read_zoo_entry(lander, "LunarLander-v3", "").entry_name == "LunarLander-v2");
  CHECK(read_zoo_entry(lander, "LunarLander-v2", "").env_id == "LunarLander-v3");
  CHECK(read_zoo_entry(file, "Acrobot-v1", "").entry_name == "default");
  CHECK(read_zoo_entry(file, "Acrobot-v1", "ppo").algorithm == "PPO");
}

TEST_CASE("zoo import: a tqc.yml entry becomes a TQC experiment", "[zoo][tqc]") {
  TempDir dir("zoo_tqc");
  Registry registry = make_builtin_registry();
  const std::string file = write_file(dir, "tqc.yml", R"zoo(# as rl-zoo's hyperparams/tqc.yml
Pendulum-v1:
  n_timesteps: 20000
  policy: 'MlpPolicy'
  learning_rate: !!float 1e-3
MountainCarContinuous-v0:
  n_timesteps: !!float 50000
  policy: 'MlpPolicy'
  learning_rate: lin_7.3e-4
  buffer_size: 50000
  batch_size: 512
  ent_coef: 0.1
  train_freq: 32
  gradient_steps: 32
  gamma: 0.9999
  tau: 0.01
  learning_starts: 0
  use_sde: True
  top_quantiles_to_drop_per_net: 5
  policy_kwargs: "dict(log_std_init=-3.67, net_arch=[64, 64], n_quantiles=20, n_critics=3)"
)zoo");
  // The algorithm from the file name; the zoo's Pendulum entry is configs/pendulum_tqc.yaml.
  const Experiment p = load_zoo_experiment(file, "Pendulum-v1", "", {}, registry);
  CHECK(p.algo.id == "TQC");
  const YAML::Node pendulum =
      translate_zoo_entry(read_zoo_entry(file, "Pendulum-v1", ""), registry).experiment;
  CHECK(pendulum["algo"]["id"].as<std::string>() == "TQC");
  CHECK(pendulum["algo"]["learning_rate"].as<double>() == 1e-3);
  CHECK(pendulum["run"]["total_timesteps"].as<double>() == 20000);

  const ZooImport imported =
      translate_zoo_entry(read_zoo_entry(file, "MountainCarContinuous-v0", ""), registry);
  const YAML::Node a = imported.experiment["algo"];
  CHECK(a["top_quantiles_to_drop_per_net"].as<int>() == 5);
  CHECK(a["use_sde"].as<bool>());
  CHECK(a["ent_coef"].as<std::string>() == "0.1");
  CHECK(a["policy"]["n_quantiles"].as<int>() == 20);
  CHECK(a["policy"]["n_critics"].as<int>() == 3);
  CHECK(a["policy"]["log_std_init"].as<double>() == -3.67);
  // The translation is an experiment rlrun reads, with every value where TQC keeps it.
  const Experiment m = load_zoo_experiment(file, "MountainCarContinuous-v0", "", {}, registry);
  CHECK(m.algo.id == "TQC");
  const std::string text = experiment_text(imported);
  CHECK_THAT(text, Catch::Contains("entry 'MountainCarContinuous-v0' (TQC)"));
  // --algo tqc for a file named otherwise; a policy key TQC does not have is named.
  const std::string renamed = write_file(dir, "tuned.yml",
                                         "Pendulum-v1:\n  n_timesteps: 1000\n"
                                         "  policy: 'MlpPolicy'\n");
  CHECK(read_zoo_entry(renamed, "Pendulum-v1", "tqc").algorithm == "TQC");
  TempDir bad_dir("zoo_tqc_bad");
  const std::string bad = write_file(bad_dir, "tqc.yml",
                                     "Pendulum-v1:\n  n_timesteps: 1000\n  policy: 'MlpPolicy'\n"
                                     "  policy_kwargs: \"dict(n_quantile=5)\"\n");
  CHECK_THAT(import_error(bad, "Pendulum-v1"), Catch::Contains("n_quantiles"));
}

TEST_CASE("zoo import: CnnPolicy is NatureCNN with SB3's defaults and kwargs", "[zoo]") {
  TempDir dir("zoo_cnn");
  Registry registry = make_builtin_registry();
  const std::string file = write_file(dir, "ppo.yml", R"zoo(CarRacing-v3:
  n_timesteps: 1000
  policy: 'CnnPolicy'
  policy_kwargs: "dict(features_extractor_kwargs=dict(features_dim=256), normalize_images=False)"
CartPole-v1:
  n_timesteps: 1000
  policy: 'CnnPolicy'
  policy_kwargs: "dict(net_arch=dict(pi=[64], vf=[64]))"
)zoo");
  const YAML::Node car =
      translate_zoo_entry(read_zoo_entry(file, "CarRacing-v3", ""), registry).experiment;
  CHECK(car["algo"]["policy"]["features_extractor_class"].as<std::string>() == "NatureCNN");
  CHECK(car["algo"]["policy"]["net_arch"].IsSequence());
  CHECK(car["algo"]["policy"]["net_arch"].size() == 0);
  CHECK(car["algo"]["policy"]["features_dim"].as<int>() == 256);
  CHECK(car["algo"]["policy"]["normalize_images"].as<bool>() == false);
  const YAML::Node pole =
      translate_zoo_entry(read_zoo_entry(file, "CartPole-v1", ""), registry).experiment;
  CHECK(pole["algo"]["policy"]["net_arch"]["pi"][0].as<int>() == 64);
  // DQN's CnnPolicy (the zoo's atari entry for dqn.yml).
  const std::string dqn = write_file(dir, "dqn.yml", R"zoo(atari:
  policy: 'CnnPolicy'
  n_timesteps: !!float 1e7
  buffer_size: 100000
  policy_kwargs: "dict(features_extractor_kwargs=dict(features_dim=256))"
)zoo");
  const YAML::Node q = translate_zoo_entry(read_zoo_entry(dqn, "atari", ""), registry).experiment;
  CHECK(q["algo"]["id"].as<std::string>() == "DQN");
  CHECK(q["algo"]["policy"]["features_extractor_class"].as<std::string>() == "NatureCNN");
  CHECK(q["algo"]["policy"]["net_arch"].size() == 0);
  CHECK(q["algo"]["policy"]["features_dim"].as<int>() == 256);
  // The off-policy CnnPolicy: SB3's net_arch for it is [256, 256] (TD3Policy's MLP default is
  // [400, 300]; SACPolicy's and TQCPolicy's is [256, 256] either way), unless set.
  const std::string td3 = write_file(dir, "td3.yml", R"zoo(CarRacing-v3:
  policy: 'CnnPolicy'
  n_timesteps: 1000
CarRacing-v2:
  policy: 'CnnPolicy'
  n_timesteps: 1000
  policy_kwargs: "dict(net_arch=[64], share_features_extractor=False)"
)zoo");
  const YAML::Node t = translate_zoo_entry(read_zoo_entry(td3, "CarRacing-v3", ""), registry)
                           .experiment["algo"]["policy"];
  CHECK(t["features_extractor_class"].as<std::string>() == "NatureCNN");
  CHECK(t["net_arch"].as<std::vector<int>>() == std::vector<int>{256, 256});
  const YAML::Node t2 = translate_zoo_entry(read_zoo_entry(td3, "CarRacing-v2", ""), registry)
                            .experiment["algo"]["policy"];
  CHECK(t2["net_arch"].as<std::vector<int>>() == std::vector<int>{64});
  CHECK(t2["share_features_extractor"].as<bool>() == false);
  for (const std::string algo : {"sac", "tqc", "ddpg"}) {
    const std::string f = write_file(dir, algo + ".yml",
                                     "CarRacing-v3:\n  n_timesteps: 1000\n  policy: 'CnnPolicy'\n");
    const YAML::Node p =
        translate_zoo_entry(read_zoo_entry(f, "CarRacing-v3", ""), registry).experiment["algo"];
    INFO(algo);
    CHECK(p["policy"]["features_extractor_class"].as<std::string>() == "NatureCNN");
    CHECK(p["policy"]["net_arch"].IsDefined() == (algo == "ddpg"));
  }
}

TEST_CASE("zoo import: activation_fn nn.GELU, as in the zoo's PPO CarRacing-v3 entry", "[zoo]") {
  TempDir dir("zoo_gelu");
  Registry registry = make_builtin_registry();
  // The zoo's policy_kwargs for PPO on CarRacing-v3 (hyperparams/ppo.yml), over several lines.
  const std::string file = write_file(dir, "ppo.yml", R"zoo(CarRacing-v3:
  n_timesteps: !!float 4e6
  policy: 'CnnPolicy'
  use_sde: True
  sde_sample_freq: 4
  policy_kwargs: "dict(log_std_init=-2,
                       ortho_init=False,
                       activation_fn=nn.GELU,
                       net_arch=dict(pi=[256], vf=[256]),
                       )"
Pendulum-v1:
  n_timesteps: 1000
  policy: 'MlpPolicy'
  policy_kwargs: "dict(activation_fn=torch.nn.GELU)"
)zoo");
  const ZooImport car = translate_zoo_entry(read_zoo_entry(file, "CarRacing-v3", ""), registry);
  const YAML::Node policy = car.experiment["algo"]["policy"];
  CHECK(policy["activation_fn"].as<std::string>() == "gelu");
  CHECK(policy["log_std_init"].as<double>() == -2.0);
  CHECK(policy["ortho_init"].as<bool>() == false);
  CHECK(policy["net_arch"]["pi"].as<std::vector<int>>() == std::vector<int>{256});
  CHECK(policy["net_arch"]["vf"].as<std::vector<int>>() == std::vector<int>{256});
  CHECK(policy["features_extractor_class"].as<std::string>() == "NatureCNN");
  const YAML::Node pendulum =
      translate_zoo_entry(read_zoo_entry(file, "Pendulum-v1", ""), registry).experiment;
  CHECK(pendulum["algo"]["policy"]["activation_fn"].as<std::string>() == "gelu");
}

TEST_CASE("zoo import: the image wrappers of the zoo's CarRacing and atari entries", "[zoo]") {
  TempDir dir("zoo_images");
  Registry registry = make_builtin_registry();
  // The current zoo (Gymnasium 1.0) and the zoo of SB3 2.4's time (Gymnasium 0.29 paths).
  const std::string file = write_file(dir, "ppo.yml", R"zoo(CarRacing-v3:
  env_wrapper:
    - rl_zoo3.wrappers.FrameSkip:
        skip: 2
    - rl_zoo3.wrappers.YAMLCompatResizeObservation:
        shape: [64, 64]
    - gymnasium.wrappers.transform_observation.GrayscaleObservation:
        keep_dim: true
  frame_stack: 2
  normalize: "{'norm_obs': False, 'norm_reward': True}"
  n_timesteps: !!float 4e6
  policy: 'CnnPolicy'
CarRacing-v2:
  env_wrapper:
    - rl_zoo3.wrappers.FrameSkip:
        skip: 2
    - gymnasium.wrappers.resize_observation.ResizeObservation:
        shape: 64
    - gymnasium.wrappers.gray_scale_observation.GrayScaleObservation:
        keep_dim: true
  frame_stack: 2
  n_timesteps: !!float 4e6
  policy: 'CnnPolicy'
atari:
  env_wrapper:
    - stable_baselines3.common.atari_wrappers.AtariWrapper
  frame_stack: 4
  policy: 'CnnPolicy'
  n_timesteps: !!float 1e7
)zoo");
  auto wrappers = [&](const std::string& env) {
    const ZooImport imported = translate_zoo_entry(read_zoo_entry(file, env, ""), registry);
    std::vector<std::string> ids;
    for (const auto& w : imported.experiment["env"]["wrappers"])
      ids.push_back(w["id"].as<std::string>());
    return std::make_pair(ids, imported.experiment["env"]["wrappers"]);
  };
  const auto [v3, v3_yaml] = wrappers("CarRacing-v3");
  CHECK(v3 == std::vector<std::string>{"FrameSkip", "ResizeObservation", "GrayscaleObservation",
                                       "FrameStack"});
  CHECK(v3_yaml[0]["skip"].as<int>() == 2);
  CHECK(v3_yaml[1]["shape"][1].as<int>() == 64);
  CHECK(v3_yaml[2]["weights"].as<std::string>() == "gymnasium");
  CHECK(v3_yaml[2]["keep_dim"].as<bool>());
  CHECK(v3_yaml[3]["layout"].as<std::string>() == "sb3");  // (64, 64, 2), as VecFrameStack
  const auto [v2, v2_yaml] = wrappers("CarRacing-v2");
  CHECK(v2_yaml[1]["shape"].as<int>() == 64);
  CHECK(v2_yaml[2]["weights"].as<std::string>() == "opencv");  // Gymnasium 0.29 called cv2
  // SB3's AtariWrapper, piece by piece (an `atari` entry applies to whatever env is named).
  const auto [atari, atari_yaml] = wrappers("atari");
  CHECK(atari == std::vector<std::string>{"NoopReset", "MaxAndSkip", "GrayscaleObservation",
                                          "ResizeObservation", "TransformReward", "FrameStack"});
  CHECK(atari_yaml[0]["noop_max"].as<int>() == 30);
  CHECK(atari_yaml[1]["skip"].as<int>() == 4);
  CHECK(atari_yaml[3]["shape"][0].as<int>() == 84);
  CHECK(atari_yaml[4]["sign"].as<bool>());
  CHECK(atari_yaml[5]["n_stack"].as<int>() == 4);
  // frame_stack asks whether `normalize` normalises observations: a norm_obs that is not a
  // boolean is refused at its line (fuzz_zoo found it escaping as a YAML exception).
  TempDir odd_dir("zoo_images_odd");
  const std::string odd = write_file(odd_dir, "ppo.yml", R"zoo(CartPole-v1:
  frame_stack: 2
  normalize: "{'norm_obs': alse, 'norm_reward': True}"
  policy: 'MlpPolicy'
)zoo");
  CHECK_THAT(import_error(odd, "CartPole-v1"),
             Catch::Contains(odd + ":3:14") && Catch::Contains("norm_obs must be True or False"));
}

TEST_CASE("zoo import: what cannot be translated is an error at the zoo file's line", "[zoo]") {
  TempDir dir("zoo_errors");
  const std::string file = write_file(dir, "ppo.yml", R"zoo(CartPole-v1:
  n_timesteps: 1000
  policy: 'MlpPolicy'
  n_stpes: 32
  policy_kwargs: "dict(net_arch=__import__('os').listdir('.'))"
Pendulum-v1:
  n_timesteps: 1000
  policy: 'CnnPolicy'
  env_wrapper: my_package.MyWrapper
Acrobot-v1:
  n_timesteps: 1000
  policy: 'MlpPolicy'
  policy_kwargs: "dict(activation_fn=nn.Sigmoid, optimizer_kwargs=dict(eps=1e-5))"
MountainCar-v0:
  n_timesteps: 1000
  policy: 'MlpPolicy'
  callback: rl_zoo3.callbacks.ParallelTrainCallback
  normalize: "dict(norm_obs=True, norm_obs_keys=['a'])"
)zoo");
  const std::string cartpole = import_error(file, "CartPole-v1");
  CHECK_THAT(cartpole, Catch::Contains(file + ":4:3") &&
                           Catch::Contains("no hyperparameter 'n_stpes'") &&
                           Catch::Contains("did you mean 'n_steps'"));
  CHECK_THAT(cartpole, Catch::Contains(file + ":5:18") && Catch::Contains("calls other than dict"));
  const std::string pendulum = import_error(file, "Pendulum-v1");
  // PPO has CnnPolicy (NatureCNN); whether the env's observations are images is checked when
  // the run starts (test_cli_cnn_policy.cpp).
  CHECK_THAT(pendulum, !Catch::Contains(file + ":8:11"));
  CHECK_THAT(pendulum, Catch::Contains(file + ":9:16") &&
                           Catch::Contains("env_wrapper my_package.MyWrapper"));
  const std::string acrobot = import_error(file, "Acrobot-v1");
  CHECK_THAT(acrobot, Catch::Contains(file + ":13:18") && Catch::Contains("nn.Sigmoid") &&
                          Catch::Contains("nn.LeakyReLU and nn.GELU"));
  const std::string car = import_error(file, "MountainCar-v0");
  CHECK_THAT(car, Catch::Contains(file + ":17:13") && Catch::Contains("ParallelTrainCallback"));
  CHECK_THAT(car, Catch::Contains(file + ":18:14") && Catch::Contains("norm_obs_keys"));
  // No entry and no default.
  CHECK_THAT(import_error(file, "MountainCarContinuous-v0"),
             Catch::Contains("no entry for MountainCarContinuous-v0 and no `default` entry"));
  // The algorithm from the file name, or --algo.
  const std::string unnamed =
      write_file(dir, "hyperparams.yml", "CartPole-v1:\n  n_timesteps: 10\n");
  CHECK_THAT(import_error(unnamed, "CartPole-v1"), Catch::Contains("pass --algo"));
}

TEST_CASE("rlrun zoo import writes a file rlrun train accepts, train --zoo trains it",
          "[zoo][cli]") {
  TempDir dir("zoo_cli");
  const std::string out = dir / "cartpole_ppo.yaml";
  const auto imported =
      rlrun::testing::run_rlrun("zoo import " + kZooData + "/ppo.yml CartPole-v1 -o " + out);
  INFO(imported.output);
  REQUIRE(imported.exit_code == 0);
  const std::string text = rlrun::testing::read_text(out);
  CHECK_THAT(text, Catch::Contains("entry 'CartPole-v1' (PPO)"));
  CHECK_THAT(text, Catch::Contains("learning_rate: lin_0.001"));
  const auto trained = rlrun::testing::run_rlrun("train " + out + " --timesteps 512 --out " +
                                                 dir.str() + " --set eval.freq=0");
  INFO(trained.output);
  CHECK(trained.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "ppo_CartPole-v1/seed0/model.zip"));

  // train --zoo with env.normalize: the model holds the statistics and eval uses them.
  const auto zoo =
      rlrun::testing::run_rlrun("train --zoo " + kZooData + "/ppo.yml --env Acrobot-v1 --out " +
                                dir.str() + " --set run.total_timesteps=4096 --set eval.freq=0");
  INFO(zoo.output);
  REQUIRE(zoo.exit_code == 0);
  const std::string model = dir / "ppo_Acrobot-v1/seed0/model.zip";
  const auto listing = rlrun::testing::run_command("unzip -l " + model);
  CHECK_THAT(listing.output, Catch::Contains("wrappers/NormalizeObservation/mean.npy") &&
                                 Catch::Contains("wrappers/NormalizeReward/var.npy"));
  const auto eval = rlrun::testing::run_rlrun("eval --model " + model + " --episodes 2");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  // Refusals: a usage error (exit 2) naming the zoo file's line.
  const auto bad = rlrun::testing::run_rlrun("zoo import " + kZooData + "/ppo.yml NoSuchEnv-v0");
  CHECK(bad.exit_code == 2);
  const auto no_env = rlrun::testing::run_rlrun("train --zoo " + kZooData + "/ppo.yml");
  CHECK(no_env.exit_code == 2);
  CHECK_THAT(no_env.output, Catch::Contains("--zoo needs --env"));
}

TEST_CASE("configs/zoo: the importer's files are experiments rlrun reads", "[zoo][configs]") {
  const std::string dir = std::string(RLRUN_SOURCE_DIR) + "/configs/zoo";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path().string());
    ++files;
    CHECK_THAT(rlrun::testing::read_text(entry.path().string()),
               Catch::StartsWith("# Imported by `rlrun zoo import`"));
    Registry registry = make_builtin_registry();
    CHECK_NOTHROW(load_experiment(entry.path().string(), {}, registry));
  }
  CHECK(files >= 14);
}

TEST_CASE("zoo import: a HER entry (replay_buffer_class, replay_buffer_kwargs as a Python dict)",
          "[zoo][her]") {
  TempDir dir("zoo_her");
  Registry registry = make_builtin_registry();
  // The shape of rl-zoo's her entries (hyperparams/tqc.yml FetchReach-v1), on a goal env rlrun has.
  const std::string file = write_file(dir, "dqn.yml", R"zoo(BitFlippingEnv-v0:
  n_timesteps: 3000
  policy: 'MultiInputPolicy'
  learning_starts: 100
  replay_buffer_class: HerReplayBuffer
  replay_buffer_kwargs: "dict(
    goal_selection_strategy='final',
    n_sampled_goal=2,
  )"
)zoo");
  const ZooImport imported =
      translate_zoo_entry(read_zoo_entry(file, "BitFlippingEnv-v0", ""), registry);
  const YAML::Node& a = imported.experiment["algo"];
  CHECK(a["replay_buffer_class"].as<std::string>() == "HerReplayBuffer");
  CHECK(a["replay_buffer_kwargs"]["goal_selection_strategy"].as<std::string>() == "final");
  CHECK(a["replay_buffer_kwargs"]["n_sampled_goal"].as<int>() == 2);
  CHECK(import_and_train(file, "dqn", "BitFlippingEnv-v0", dir / "runs", true) == "");
  // A kwarg HerReplayBuffer does not have is named with the closest one.
  TempDir bad_dir("zoo_her_bad");
  const std::string bad = write_file(bad_dir, "dqn.yml", R"zoo(BitFlippingEnv-v0:
  n_timesteps: 3000
  policy: 'MultiInputPolicy'
  replay_buffer_class: HerReplayBuffer
  replay_buffer_kwargs: "dict(n_sampled_goals=2)"
)zoo");
  CHECK_THAT(import_and_train(bad, "dqn", "BitFlippingEnv-v0", dir / "runs_bad", false),
             Catch::Contains("n_sampled_goal"));
}

TEST_CASE("zoo import: optimize_memory_usage with replay_buffer_kwargs' handle_timeout_termination",
          "[zoo][replay]") {
  TempDir dir("zoo_optimize_memory");
  Registry registry = make_builtin_registry();
  // What the zoo's atari entry's comment asks for, on CartPole.
  const std::string file = write_file(dir, "dqn.yml", R"zoo(CartPole-v1:
  n_timesteps: 600
  policy: 'MlpPolicy'
  buffer_size: 500
  learning_starts: 100
  optimize_memory_usage: True
  replay_buffer_kwargs: "dict(handle_timeout_termination=False)"
)zoo");
  const ZooImport imported = translate_zoo_entry(read_zoo_entry(file, "CartPole-v1", ""), registry);
  const YAML::Node& a = imported.experiment["algo"];
  CHECK(a["optimize_memory_usage"].as<bool>());
  CHECK_FALSE(a["handle_timeout_termination"].as<bool>());
  CHECK_FALSE(a["replay_buffer_kwargs"].IsDefined());
  CHECK(import_and_train(file, "dqn", "CartPole-v1", dir / "runs", true) == "");
  // Without it, SB3's ValueError, at the key.
  TempDir bad_dir("zoo_optimize_memory_bad");
  const std::string bad = write_file(bad_dir, "dqn.yml", R"zoo(CartPole-v1:
  n_timesteps: 600
  policy: 'MlpPolicy'
  optimize_memory_usage: True
)zoo");
  CHECK_THAT(import_and_train(bad, "dqn", "CartPole-v1", dir / "runs_bad", false),
             Catch::Contains("optimize_memory_usage") &&
                 Catch::Contains("handle_timeout_termination: false"));
}

TEST_CASE(
    "zoo import: --entry uses another env's entry (the zoo's PandaReach TQC + HER entry for "
    "GripperReach)",
    "[zoo][her]") {
  TempDir dir("zoo_entry");
  Registry registry = make_builtin_registry();
  // rl-baselines3-zoo hyperparams/tqc.yml, PandaReach-v1, as the zoo writes it.
  const std::string file = write_file(dir, "tqc.yml", R"zoo(PandaReach-v1:
  n_timesteps: !!float 20000
  policy: 'MultiInputPolicy'
  buffer_size: 1000000
  ent_coef: 'auto'
  batch_size: 256
  gamma: 0.95
  learning_rate: 0.001
  learning_starts: 1000
  normalize: True
  replay_buffer_class: HerReplayBuffer
  replay_buffer_kwargs: "dict(
    goal_selection_strategy='future',
    n_sampled_goal=4
  )"
  policy_kwargs: "dict(net_arch=[64, 64], n_critics=1)"
)zoo");
  const ZooEntry entry = read_zoo_entry(file, "GripperReach-v0", "", "PandaReach-v1");
  CHECK(entry.entry_name == "PandaReach-v1");
  CHECK(entry.env_id == "GripperReach-v0");
  const Experiment e = load_zoo_experiment(
      file, "GripperReach-v0", "",
      {"run.total_timesteps=1500", "eval.freq=0", "run.out_dir=" + dir / "runs"}, registry,
      "PandaReach-v1");
  CHECK(e.env.section.normalize.enabled);
  const TrainOutcome outcome = train_experiment(e, registry, testing::test_execution());
  CHECK(std::filesystem::exists(outcome.run_dir + "/model.zip"));
  // A missing entry is named with the closest one.
  CHECK_THROWS_WITH(read_zoo_entry(file, "GripperReach-v0", "", "PandaReach-v3"),
                    Catch::Contains("did you mean 'PandaReach-v1'"));
}

TEST_CASE("zoo import: YAML merge keys, as the zoo's MuJoCo and PyBullet sections write them",
          "[zoo][merge]") {
  TempDir dir("zoo_merge");
  Registry registry = make_builtin_registry();
  // The shape of rl-zoo's hyperparams/a2c.yml `HalfCheetah-v4: &mujoco-defaults` section and
  // its `Humanoid-v4: {<<: *mujoco-defaults, n_timesteps: ...}` entries, on rlrun's envs.
  const std::string file = write_file(dir, "a2c.yml", R"zoo(Pendulum-v1: &pendulum-defaults
  normalize: true
  n_envs: 4
  n_timesteps: !!float 1e6
  policy: 'MlpPolicy'
  ent_coef: 0.0
  use_rms_prop: True

MountainCarContinuous-v0:
  <<: *pendulum-defaults
  n_timesteps: !!float 2e6

LunarLanderContinuous-v3:
  <<: [*pendulum-defaults, {gamma: 0.9, n_envs: 16}]
  n_envs: 8
)zoo");
  const YAML::Node car =
      translate_zoo_entry(read_zoo_entry(file, "MountainCarContinuous-v0", ""), registry)
          .experiment;
  CHECK(car["run"]["total_timesteps"].as<double>() == 2e6);
  CHECK(car["env"]["n_envs"].as<int>() == 4);
  CHECK(car["env"]["normalize"].as<bool>());
  CHECK(car["algo"]["use_rms_prop"].as<bool>());
  CHECK_FALSE(car["algo"]["<<"]);
  const Experiment lander = load_zoo_experiment(file, "LunarLanderContinuous-v3", "", {}, registry);
  CHECK(lander.env.section.n_envs == 8);
  CHECK(lander.algo.params.resolved()["gamma"].as<double>() == 0.9);
  CHECK(lander.run.total_timesteps == 1000000);
}

TEST_CASE("zoo import: an algorithm rlrun lacks is named before anything else", "[zoo]") {
  TempDir dir("zoo_missing_algo");
  const std::string entry = "CartPole-v1:\n  n_timesteps: 1000\n  policy: 'MlpPolicy'\n";
  const std::vector<std::pair<std::string, std::string>> files{
      {"her.yml", "HER became a replay buffer"}};
  for (const auto& [name, message] : files) {
    INFO(name);
    const std::string error = import_error(write_file(dir, name, entry), "CartPole-v1");
    CHECK_THAT(error, Catch::Contains(message) && !Catch::Contains("pass --algo"));
  }
  CHECK(read_zoo_entry(write_file(dir, "trpo.yml", entry), "CartPole-v1", "").algorithm == "TRPO");
  CHECK(read_zoo_entry(write_file(dir, "ars.yml", entry), "CartPole-v1", "").algorithm == "ARS");
  // MaskablePPO and RecurrentPPO are rlrun's (algos/ppo_mask/, algos/ppo_recurrent/), by
  // rl-zoo's name or sb3-contrib's.
  for (const char* name : {"ppo_mask", "maskable_ppo", "MaskablePPO"})
    CHECK(read_zoo_entry(write_file(dir, "tuned.yml", entry), "CartPole-v1", name).algorithm ==
          "MaskablePPO");
  for (const char* name : {"ppo_lstm", "recurrent_ppo", "RecurrentPPO"})
    CHECK(read_zoo_entry(write_file(dir, "tuned.yml", entry), "CartPole-v1", name).algorithm ==
          "RecurrentPPO");
  CHECK(read_zoo_entry(write_file(dir, "ppo_lstm.yml", entry), "CartPole-v1", "").algorithm ==
        "RecurrentPPO");
}

TEST_CASE(
    "zoo import: a gymnasium: env takes the entry of its Gymnasium id, run names are one "
    "path component",
    "[zoo]") {
  TempDir dir("zoo_gymnasium");
  Registry registry = make_builtin_registry();
  const std::string file = write_file(dir, "ppo.yml",
                                      "LunarLander-v2:\n  n_timesteps: 1000\n"
                                      "  policy: 'MlpPolicy'\n  n_steps: 64\n"
                                      "default:\n  n_timesteps: 5\n");
  const ZooEntry lander = read_zoo_entry(file, "gymnasium:LunarLander-v3", "");
  CHECK(lander.entry_name == "LunarLander-v2");
  CHECK(lander.env_id == "gymnasium:LunarLander-v3");
  const ZooImport imported = translate_zoo_entry(lander, registry);
  CHECK(imported.experiment["env"]["id"].as<std::string>() == "gymnasium:LunarLander-v3");
  CHECK(imported.experiment["run"]["name"].as<std::string>() == "ppo_gymnasium-LunarLander-v3");
  CHECK(imported.experiment["algo"]["n_steps"].as<int>() == 64);
  CHECK(read_zoo_entry(file, "gymnasium:CartPole-v1", "").entry_name == "default");
  CHECK(zoo_run_name("PPO", "gymnasium:ALE/Pong-v5") == "ppo_gymnasium-ALE-Pong-v5");
  CHECK(zoo_run_name("SAC", "python:my_pkg.envs:Arm") == "sac_python-my_pkg.envs-Arm");
  CHECK(zoo_run_name("DQN", "CartPole-v1") == "dqn_CartPole-v1");
  CHECK(zoo_run_name("DQN", "../../x y\n") == "dqn_..-..-x-y-");
  CHECK(zoo_run_name("DQN", std::string(500, 'x')).size() == 104);
}

TEST_CASE("zoo import: the zoo's SAC CarRacing entry names a pretrained autoencoder: refused",
          "[zoo]") {
  // rl-baselines3-zoo's sac.yml and tqc.yml CarRacing entries read an autoencoder trained by
  // another project (aae-train-donkeycar) from logs/car_racing_rgb_160.pkl.
  TempDir dir("zoo_car_racing_sac");
  const std::string file = write_file(dir, "sac.yml", R"zoo(CarRacing-v3:
  env_wrapper:
    - rl_zoo3.wrappers.FrameSkip:
        skip: 2
    - ae.wrapper.AutoencoderWrapper:
        ae_path: "logs/car_racing_rgb_160.pkl"
    - rl_zoo3.wrappers.HistoryWrapper:
        horizon: 2
  normalize: True
  n_envs: 2
  n_timesteps: !!float 1e6
  policy: 'MlpPolicy'
)zoo");
  CHECK_THAT(import_error(file, "CarRacing-v3"),
             Catch::Contains("ae.wrapper.AutoencoderWrapper") && Catch::Contains("sac.yml:5"));
}
