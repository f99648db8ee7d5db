// Every Gymnasium space kind end to end through the real binary (issue 16): the probe envs
// (envs/probe/) trained with `rlrun train` and evaluated from the model file alone with
// `rlrun eval --model`, reaching the optimum: on the identity envs the return equals the episode
// length (20 steps here), SimpleMultiObsEnv-v0 walks the 6 moves from cell 0 (return 0.5),
// DictReach-v0 reaches the goal in every episode. Each run takes 1-3 s.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;

double number_after(const std::string& output, const std::string& key) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex(key + " = (-?[0-9.]+)")));
  return std::stod(m[1]);
}

// numpy.load of a model file as an SB3 user would do it: "<name> <dtype> <shape>" per tensor.
std::string model_tensors(const std::string& model_zip) {
  const auto r =
      run_command("/usr/bin/python3 " + kSource + "/tests/data/numpy_load_model.py " + model_zip);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  return r.output;
}

// Trains `algo` on `env` (a YAML flow map of the env section) and evaluates the model file;
// returns eval's output.
std::string train_and_eval(TempDir& dir, const std::string& name, const std::string& env,
                           const std::string& algo, int64_t steps, int episodes = 10) {
  const std::string config = dir / (name + ".yaml");
  std::ofstream(config) << "run: {name: " << name << ", seed: 1, total_timesteps: " << steps
                        << ", out_dir: " << dir.str() << "}\n"
                        << "env: " << env << "\n"
                        << "algo: " << algo << "\n";
  const auto train = run_rlrun("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / (name + "/seed1/model.zip");
  const auto eval = run_rlrun("eval --model " + model + " --episodes " + std::to_string(episodes));
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  return eval.output;
}

// Identity envs: short episodes, a short horizon (the best action does not depend on the
// future), small rollouts.
const std::string kPpo =
    "{id: PPO, n_steps: 64, batch_size: 64, n_epochs: 10, learning_rate: 0.001, gamma: 0.5}";
const std::string kA2c = "{id: A2C, n_steps: 8, learning_rate: 0.003, gamma: 0.5}";

std::string identity(const std::string& id, const std::string& kwargs = "{}") {
  return "{id: " + id + ", n_envs: 4, max_episode_steps: 20, kwargs: " + kwargs + "}";
}

}  // namespace

TEST_CASE("spaces: Discrete observations and actions (IdentityEnv-v0), PPO and A2C",
          "[cli][spaces]") {
  TempDir dir("spaces_discrete");
  const std::string env = identity("IdentityEnv-v0");
  CHECK(number_after(train_and_eval(dir, "ppo", env, kPpo, 20000), "mean_reward") == 20.0);
  CHECK(number_after(train_and_eval(dir, "a2c", env, kA2c, 20000), "mean_reward") == 20.0);
}

TEST_CASE("spaces: Box observations and actions (IdentityEnvBox-v0), PPO", "[cli][spaces]") {
  TempDir dir("spaces_box");
  const std::string env = identity("IdentityEnvBox-v0", "{eps: 0.1}");
  CHECK(number_after(train_and_eval(dir, "ppo", env, kPpo, 30000), "mean_reward") == 20.0);
}

TEST_CASE("spaces: MultiDiscrete observations and actions, PPO and A2C", "[cli][spaces]") {
  TempDir dir("spaces_multi_discrete");
  const std::string env = identity("IdentityEnvMultiDiscrete-v0");
  CHECK(number_after(train_and_eval(dir, "ppo", env, kPpo, 20000), "mean_reward") == 20.0);
  CHECK(number_after(train_and_eval(dir, "a2c", env, kA2c, 20000), "mean_reward") == 20.0);
  // SB3's MultiCategorical head: sum(nvec) = 8 logits.
  const std::string tensors = model_tensors(dir / "ppo/seed1/model.zip");
  INFO(tensors);
  CHECK(tensors.find("action_net.weight float32 (8, 64)") != std::string::npos);
}

TEST_CASE("spaces: MultiBinary observations and actions, PPO and A2C", "[cli][spaces]") {
  TempDir dir("spaces_multi_binary");
  const std::string env = identity("IdentityEnvMultiBinary-v0");
  CHECK(number_after(train_and_eval(dir, "ppo", env, kPpo, 20000), "mean_reward") == 20.0);
  CHECK(number_after(train_and_eval(dir, "a2c", env, kA2c, 20000), "mean_reward") == 20.0);
}

TEST_CASE("spaces: a Dict of MultiBinary, Discrete and Box keys (SimpleMultiObsEnv-v0), PPO",
          "[cli][spaces]") {
  TempDir dir("spaces_dict_discrete");
  const auto train = run_rlrun("train " + kSource +
                               "/configs/simplemultiobs_ppo.yaml --set run.out_dir=" + dir.str() +
                               " --set env.kwargs.random_start=false" + " --set obs_log.freq=800");
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run = dir / "simplemultiobs_ppo/seed1";
  const auto eval = run_rlrun("eval --model " + run + "/model.zip --episodes 5");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(number_after(eval.output, "mean_reward") == 0.5);
  CHECK(number_after(eval.output, "mean_ep_length") == 6.0);
  // The model file names the Dict space (meta.json, Space::describe()) and SB3's tensor names:
  // MultiInputPolicy's Flatten extractors have no parameters; the towers take 4 + 4 + 5 inputs.
  const std::string tensors = model_tensors(run + "/model.zip");
  INFO(tensors);
  CHECK(tensors.find("mlp_extractor.policy_net.0.weight float32 (64, 13)") != std::string::npos);
  CHECK(tensors.find("features_extractor") == std::string::npos);
  // The observation log holds the flat Dict observations; record --from-obs draws them (one
  // chunk: 800 steps of 8 envs, 100 rows of env 0).
  const std::string chunk = run + "/obs_log/obs_0000000800.npy";
  const auto record = run_rlrun("record --from-obs " + chunk + " --env SimpleMultiObsEnv-v0" +
                                " --size 160x160 --output " + (dir / "log.mp4"));
  INFO(record.output);
  CHECK(record.exit_code == 0);
  CHECK(fs::exists(dir / "log.mp4"));
  const auto wrong = run_rlrun("record --from-obs " + chunk + " --env DictReach-v0 --output " +
                               (dir / "wrong.mp4"));
  CHECK(wrong.exit_code == 2);
  CHECK(wrong.output.find("4 floats: 'goal' [0, 2), 'position' [2, 4)") != std::string::npos);
}

TEST_CASE("spaces: a Dict of Box keys with a Box action (DictReach-v0), PPO, plain and wrapped",
          "[cli][spaces]") {
  TempDir dir("spaces_dict_box");
  const std::string config = kSource + "/configs/dictreach_ppo.yaml --set run.out_dir=" + dir.str();
  const auto plain = run_rlrun("train " + config);
  INFO(plain.output);
  REQUIRE(plain.exit_code == 0);
  const auto eval =
      run_rlrun("eval --model " + dir / "dictreach_ppo/seed1/model.zip --episodes 20");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(number_after(eval.output, "success_rate") == 1.0);
  // FrameStack and NormalizeObservation key by key; the statistics travel in the model file.
  const auto wrapped =
      run_rlrun("train " + config + " --set run.name=wrapped --set run.total_timesteps=8192" +
                " --set 'env.wrappers=[{id: NormalizeObservation}, {id: FrameStack, n_stack: 2}]'");
  INFO(wrapped.output);
  REQUIRE(wrapped.exit_code == 0);
  const auto wrapped_eval =
      run_rlrun("eval --model " + dir / "wrapped/seed1/model.zip --episodes 3");
  INFO(wrapped_eval.output);
  CHECK(wrapped_eval.exit_code == 0);
}

TEST_CASE("spaces: list and check-env show Dict spaces key by key", "[cli][spaces]") {
  const auto env = run_rlrun("list SimpleMultiObsEnv-v0");
  CHECK(env.exit_code == 0);
  CHECK(env.output.find("observation_space  Dict (10 floats, keys in sorted order)") !=
        std::string::npos);
  CHECK(env.output.find("'row': Discrete(4)  floats [4, 5)") != std::string::npos);
  CHECK(env.output.find("action_space       Discrete(4)") != std::string::npos);
  const auto ppo = run_rlrun("list PPO");
  CHECK(ppo.output.find("action spaces      Box, Discrete, MultiDiscrete, MultiBinary") !=
        std::string::npos);
  const auto check = run_rlrun("check-env DictReach-v0 --episodes 2");
  CHECK(check.exit_code == 0);
  CHECK(check.output.find("'position': Box(-1.0, 1.0, (2,), float32)  floats [2, 4)") !=
        std::string::npos);
}

// The same optima for seeds 1, 2 and 3, random starts in SimpleMultiObsEnv-v0, and GridWorld-v0's
// MultiDiscrete observations without the OneHotObservation wrapper (about 30 s).
TEST_CASE("spaces: every probe env's optimum for seeds 1, 2, 3", "[cli][spaces][.slow]") {
  TempDir dir("spaces_seeds");
  for (const char* seed : {"1", "2", "3"}) {
    const std::string set = " --seed " + std::string(seed) + " --set run.out_dir=" + dir.str();
    for (const char* id :
         {"IdentityEnv-v0", "IdentityEnvMultiDiscrete-v0", "IdentityEnvMultiBinary-v0"}) {
      for (const std::string& algo : {kPpo, kA2c}) {
        INFO(id << " " << algo << " seed " << seed);
        const std::string name =
            std::string("s") + seed + "_" + id + (algo == kPpo ? "_ppo" : "_a2c");
        const std::string config = dir / (name + ".yaml");
        std::ofstream(config) << "run: {name: " << name << ", total_timesteps: 20000}\n"
                              << "env: " << identity(id) << "\nalgo: " << algo << "\n";
        REQUIRE(run_rlrun("train " + config + set).exit_code == 0);
        const auto eval = run_rlrun("eval --model " + dir / (name + "/seed" + seed + "/model.zip"));
        CHECK(number_after(eval.output, "mean_reward") == 20.0);
      }
    }
    for (const char* config : {"dictreach_ppo", "simplemultiobs_ppo"}) {
      INFO(config << " seed " << seed);
      REQUIRE(run_rlrun("train " + kSource + "/configs/" + config + ".yaml" + set).exit_code == 0);
      const auto eval =
          run_rlrun("eval --model " + dir / (std::string(config) + "/seed" + seed + "/model.zip") +
                    " --episodes 20");
      CHECK(number_after(eval.output, "success_rate") == 1.0);
    }
    const std::string grid = dir / "grid.yaml";
    std::ofstream(grid) << "run: {name: grid, total_timesteps: 30000}\n"
                        << "env: {id: GridWorld-v0, n_envs: 8}\n"
                        << "algo: {id: PPO, n_steps: 64, batch_size: 128, n_epochs: 10, "
                           "learning_rate: 0.001, gamma: 0.95}\n";
    REQUIRE(run_rlrun("train " + grid + set).exit_code == 0);
    const auto eval =
        run_rlrun("eval --model " + dir / ("grid/seed" + std::string(seed) + "/model.zip"));
    CHECK(number_after(eval.output, "mean_reward") == -8.0);
  }
}

TEST_CASE("spaces: off-policy algorithms take Dict observations (SAC learns DictReach-v0)",
          "[cli][spaces]") {
  TempDir dir("spaces_dict_sac");
  const auto train = run_rlrun("--threads 1 train " + kSource +
                               "/configs/dictreach_sac.yaml --set run.out_dir=" + dir.str());
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run = dir / "dictreach_sac/seed1";
  const auto eval = run_rlrun("eval --model " + run + "/model.zip --episodes 20");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(number_after(eval.output, "success_rate") == 1.0);
  // SB3's names for a MultiInputPolicy SAC: the Flatten extractors have no parameters; the
  // actor and each critic take goal (2) + position (2) [+ action (2)] inputs.
  const std::string tensors = model_tensors(run + "/model.zip");
  INFO(tensors);
  CHECK(tensors.find("actor.latent_pi.0.weight float32 (64, 4)") != std::string::npos);
  CHECK(tensors.find("critic.qf0.0.weight float32 (64, 6)") != std::string::npos);
  CHECK(tensors.find("features_extractor") == std::string::npos);
}

TEST_CASE("spaces: DQN on a Dict of MultiBinary, Discrete and Box keys, TD3 and DDPG on Dict",
          "[cli][spaces]") {
  TempDir dir("spaces_dict_offpolicy");
  // The Discrete key reaches the Q-network one-hot: 4 + 4 + 5 inputs, as PPO's towers.
  const std::string dqn =
      "{id: DQN, learning_rate: 1.0e-3, buffer_size: 10000, learning_starts: 500, batch_size: 64,"
      " gamma: 0.95, target_update_interval: 100, exploration_fraction: 0.3,"
      " exploration_final_eps: 0.05, policy: {net_arch: [64, 64]}}";
  const std::string out = train_and_eval(
      dir, "dqn", "{id: SimpleMultiObsEnv-v0, n_envs: 1, kwargs: {random_start: false}}", dqn,
      10000, 5);
  CHECK(number_after(out, "mean_reward") == 0.5);
  CHECK(number_after(out, "mean_ep_length") == 6.0);
  const std::string tensors = model_tensors(dir / "dqn/seed1/model.zip");
  INFO(tensors);
  CHECK(tensors.find("q_net.0.weight float32 (64, 13)") != std::string::npos);
  // TD3 and DDPG train and evaluate on DictReach (a few hundred steps: the plumbing).
  for (const std::string algo : {"TD3", "DDPG"}) {
    const std::string name = algo == "TD3" ? "td3" : "ddpg";
    const std::string eval = train_and_eval(
        dir, name, "{id: DictReach-v0, n_envs: 1}",
        "{id: " + algo + ", learning_starts: 100, batch_size: 32, policy: {net_arch: [32]}}", 400,
        2);
    CHECK(eval.find("success_rate") != std::string::npos);
  }
}
