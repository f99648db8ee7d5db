// SB3 model files (runtime/io/sb3/sb3_model_file.hpp) against what the real SB3 2.4.1 did with
// them: tests/data/sb3/<case>/ holds a model.zip SB3 trained and saved, observations, SB3's
// deterministic predict() on them and its episode returns on seeded resets
// (scripts/data/make_sb3_models.sh made them with SB3's source and Debian's torch).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/torch_file_writer.hpp"
#include "rlrun/core/torch_state_dict.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/env/graph_policy.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/sb3_test_data.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

std::string case_dir(const std::string& name) { return sb3_case_dir(name); }
Tensor read_npy(const std::string& path) { return read_npy_file(path); }

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

struct Sb3Case {
  const char* name;
  const char* env_id;
  const char* algorithm;
};

const Sb3Case kCases[] = {
    {"ppo_cartpole", "CartPole-v1", "PPO"},
    {"a2c_cartpole", "CartPole-v1", "A2C"},
    {"dqn_cartpole", "CartPole-v1", "DQN"},
    {"ppo_pendulum", "Pendulum-v1", "PPO"},
    {"sac_pendulum", "Pendulum-v1", "SAC"},
    {"td3_pendulum", "Pendulum-v1", "TD3"},
    {"ddpg_pendulum", "Pendulum-v1", "DDPG"},
    // Trained inside VecNormalize; vecnormalize.pkl beside model.zip (rl-zoo's layout).
    {"ppo_pendulum_vecnormalize", "Pendulum-v1", "PPO"},
    // gSDE (use_sde=True), as rl-zoo trains many continuous tasks.
    {"ppo_sde_pendulum", "Pendulum-v1", "PPO"},
    {"sac_sde_pendulum", "Pendulum-v1", "SAC"},
    // sb3-contrib 2.4.0.
    {"qrdqn_cartpole", "CartPole-v1", "QRDQN"},
    {"tqc_pendulum", "Pendulum-v1", "TQC"},
    {"trpo_pendulum", "Pendulum-v1", "TRPO"},
    {"maskable_ppo_cartpole", "CartPole-v1", "MaskablePPO"},
    // actions.npy from a zero LSTM state per observation; returns.json carries the state
    // along each episode, as rlrun eval does.
    {"recurrent_ppo_cartpole", "CartPole-v1", "RecurrentPPO"},
    {"recurrent_ppo_pendulum", "Pendulum-v1", "RecurrentPPO"},
};

// What the env's frozen NormalizeObservation does to an observation: VecNormalize.normalize_obs
// with the file's defaults (epsilon 1e-8, clip_obs 10), in double as both compute it.
void normalize_observations(const TensorMap& statistics, Eigen::MatrixXf& observations) {
  const auto mean = statistics.find("wrappers/NormalizeObservation/mean");
  if (mean == statistics.end()) return;
  const Tensor& var = statistics.at("wrappers/NormalizeObservation/var");
  for (Eigen::Index i = 0; i < observations.rows(); ++i)
    for (Eigen::Index j = 0; j < observations.cols(); ++j) {
      const double z = (observations(i, j) - mean->second.data<double>()[i]) /
                       std::sqrt(var.data<double>()[i] + 1e-8);
      observations(i, j) = static_cast<float>(std::clamp(z, -10.0, 10.0));
    }
}

// rlrun's deterministic actions on the case's observations (act_dim x n).
Eigen::MatrixXf rlrun_actions(const Sb3Case& c, Eigen::MatrixXf& observations) {
  LoadedModel model = load_model(case_dir(c.name) + "/model.zip", builtin_registry(),
                                 {std::string("env.id=") + c.env_id});
  CHECK(model.file.meta.algorithm == c.algorithm);
  const Tensor obs = read_npy(case_dir(c.name) + "/observations.npy");
  REQUIRE(obs.dtype == DType::kFloat32);
  REQUIRE(obs.shape.size() == 2);
  // (n, obs_dim) C order is obs_dim x n column-major: one observation per column.
  observations = Eigen::Map<const Eigen::MatrixXf>(obs.data<float>(), obs.shape[1], obs.shape[0]);
  normalize_observations(model.file.wrapper_statistics, observations);
  Eigen::MatrixXf actions;
  model.algorithm->predict(observations, /*deterministic=*/true, actions);
  return actions;
}

}  // namespace

TEST_CASE("SB3 model files give SB3's deterministic actions", "[sb3]") {
  for (const Sb3Case& c : kCases) {
    INFO(c.name);
    Eigen::MatrixXf observations;
    const Eigen::MatrixXf actions = rlrun_actions(c, observations);
    const Tensor expected = read_npy(case_dir(c.name) + "/actions.npy");
    REQUIRE(actions.cols() == expected.shape[0]);
    REQUIRE(expected.shape[0] == 1000);
    if (expected.dtype == DType::kInt64) {  // Discrete: exactly SB3's
      REQUIRE(actions.rows() == 1);
      int differ = 0;
      for (int i = 0; i < actions.cols(); ++i)
        differ += static_cast<int64_t>(actions(0, i)) != expected.data<int64_t>()[i];
      CHECK(differ == 0);
    } else {  // Box: within 1e-5 of SB3's float32 actions
      REQUIRE(expected.dtype == DType::kFloat32);
      const Eigen::Map<const Eigen::MatrixXf> sb3(expected.data<float>(), actions.rows(),
                                                  actions.cols());
      CHECK((actions - sb3).cwiseAbs().maxCoeff() <= 1e-5f);
    }
  }
}

// A fixture's uint8 images (N, H, W, C) as N columns of floats, the layout predict() takes.
static Eigen::MatrixXf image_columns(const std::string& npy, const std::vector<int64_t>& shape) {
  const Tensor images = read_npy(npy);
  REQUIRE(images.dtype == DType::kUInt8);
  REQUIRE(images.shape == shape);
  const int64_t n = shape[0], dim = shape[1] * shape[2] * shape[3];
  Eigen::MatrixXf columns(dim, n);
  for (int64_t i = 0; i < n * dim; ++i)
    columns(i % dim, i / dim) = static_cast<float>(images.data<uint8_t>()[i]);
  return columns;
}

TEST_CASE("SB3's CnnPolicy files give SB3's actions on the same images", "[sb3]") {
  // PPO's CnnPolicy (NatureCNN, features_dim 64) on GripperLift-v0's pixel spaces: the file
  // holds the channels-first space of SB3's VecTransposeImage and the one extractor under
  // three names; rlrun reads them as its own CnnPolicy on the env's channels-last images.
  const std::string dir = case_dir("ppo_cnn_gripper_pixels");
  LoadedModel model = load_model(
      dir + "/model.zip", builtin_registry(),
      {"env.id=GripperLift-v0", "env.kwargs.obs_type=pixels", "env.kwargs.image_size=36"});
  CHECK(model.file.meta.algorithm == "PPO");
  CHECK(model.file.tensors.count("features_extractor.cnn.0.weight") == 1);
  CHECK(model.file.tensors.count("pi_features_extractor.cnn.0.weight") == 0);
  const Eigen::MatrixXf observations = image_columns(dir + "/observations.npy", {32, 36, 36, 3});
  Eigen::MatrixXf actions;
  model.algorithm->predict(observations, /*deterministic=*/true, actions);
  const Tensor expected = read_npy(dir + "/actions.npy");
  REQUIRE(expected.shape == std::vector<int64_t>{32, 4});
  const Eigen::Map<const Eigen::MatrixXf> sb3(expected.data<float>(), 4, 32);
  CHECK((actions - sb3).cwiseAbs().maxCoeff() <= 1e-5f);
  // rlrun eval plays it on the rendered camera images.
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " eval --model " + dir +
                  "/model.zip --env GripperLift-v0 --set env.kwargs.obs_type=pixels --set "
                  "env.kwargs.image_size=36 --set env.max_episode_steps=20 --episodes 1 2>&1");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("mean_ep_length = 20.0"));
}

TEST_CASE("SB3's off-policy CnnPolicy files (DQN, SAC) give SB3's actions on the same images",
          "[sb3]") {
  // Each network has its own NatureCNN (features_dim 16): DQN's q_net and q_net_target, SAC's
  // actor, critic and critic_target, under SB3's names, which are rlrun's. The spaces are those
  // of rlrun's pixel CartPole / Pendulum (36x36 gray frames, channels last).
  struct Case {
    const char* name;
    const char* env;
    const char* algorithm;
    std::vector<const char*> extractors;
  };
  const Case cases[] = {
      {"dqn_cnn_cartpole_pixels", "CartPole-v1", "DQN", {"q_net.", "q_net_target."}},
      {"sac_cnn_pendulum_pixels", "Pendulum-v1", "SAC", {"actor.", "critic.", "critic_target."}},
  };
  const std::string pixels =
      "env.wrappers=[{id: AddRenderObservation, width: 36, height: 36}, "
      "{id: GrayscaleObservation, keep_dim: true}]";
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string dir = case_dir(c.name);
    LoadedModel model = load_model(dir + "/model.zip", builtin_registry(),
                                   {std::string("env.id=") + c.env, pixels});
    CHECK(model.file.meta.algorithm == c.algorithm);
    for (const char* owner : c.extractors)
      CHECK(model.file.tensors.count(std::string(owner) + "features_extractor.cnn.0.weight") == 1);
    CHECK(model.experiment.resolved["algo"]["policy"]["features_dim"].as<int>() == 16);
    const Eigen::MatrixXf observations = image_columns(dir + "/observations.npy", {32, 36, 36, 1});
    Eigen::MatrixXf actions;
    model.algorithm->predict(observations, /*deterministic=*/true, actions);
    const Tensor expected = read_npy(dir + "/actions.npy");
    REQUIRE(expected.numel() == actions.size());
    for (Eigen::Index i = 0; i < actions.cols(); ++i) {
      const float sb3 = expected.dtype == DType::kInt64
                            ? static_cast<float>(expected.data<int64_t>()[i])
                            : expected.data<float>()[i];
      CHECK(std::abs(actions(0, i) - sb3) <= 1e-5f);
    }
    // rlrun eval plays it on the env's own rendered frames.
    const CommandResult r = run_command(std::string(RLRUN_BINARY) + " eval --model " + dir +
                                        "/model.zip --env " + c.env + " --set '" + pixels +
                                        "' --set env.max_episode_steps=10 --episodes 1 2>&1");
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output, Catch::Contains("mean_ep_length = 10.0"));
  }
}

TEST_CASE("rlrun eval of an SB3 model file gives SB3's returns on the same seeds", "[sb3][cli]") {
  // The classic-control envs draw Gymnasium's initial state for a seed (numpy's PCG64:
  // env/numpy_random.hpp), so each seeded episode is SB3's episode.
  for (const Sb3Case& c : kCases) {
    INFO(c.name);
    // rlrun's MaskablePPO plays with the env's masks, and CartPole reports none (sb3-contrib's
    // predict without masks is the first test's).
    if (std::string(c.algorithm) == "MaskablePPO") continue;
    const nlohmann::json returns = read_json(case_dir(c.name) + "/returns.json");
    for (size_t i = 0; i < returns["seeds"].size(); ++i) {
      const int seed = returns["seeds"][i].get<int>();
      const double sb3 = returns["episode_returns"][i].get<double>();
      INFO("seed " << seed);
      const CommandResult r = run_command(std::string(RLRUN_BINARY) + " eval --model " +
                                          case_dir(c.name) + "/model.zip --env " + c.env_id +
                                          " --episodes 1 --seed " + std::to_string(seed) + " 2>&1");
      REQUIRE(r.exit_code == 0);
      const auto at = r.output.find("mean_reward = ");
      REQUIRE(at != std::string::npos);
      const double rlrun = std::stod(r.output.substr(at + 14));
      // The summary prints two decimals; Box actions within 1e-5 of SB3's move Pendulum's
      // return by far less.
      CHECK(std::abs(rlrun - sb3) <= 0.006);
    }
  }
}

TEST_CASE("SB3 model files give SB3's Q-values and action log-probabilities", "[sb3]") {
  // Actions alone hide a wrong network where one action wins everywhere (the short DQN run):
  // the logits behind the argmax are compared, DQN's as SB3's q_net output, PPO's and A2C's as
  // the Categorical's log-probabilities (log-softmax of the logits).
  for (const auto& [name, file] : {std::pair{"dqn_cartpole", "q_values.npy"},
                                   {"ppo_cartpole", "action_log_probs.npy"},
                                   {"a2c_cartpole", "action_log_probs.npy"}}) {
    INFO(name);
    const LoadedModel model = load_model(case_dir(name) + "/model.zip", builtin_registry(),
                                         {"env.id=CartPole-v1"}, {}, ModelEnv::kSpacesOnly);
    const GraphPolicy policy(build_model_graph(model, false));
    const Tensor obs = read_npy(case_dir(name) + "/observations.npy");
    const Tensor expected = read_npy(case_dir(name) + "/" + file);
    const bool log_softmax = std::string(file) == "action_log_probs.npy";
    float worst = 0;
    for (int64_t i = 0; i < obs.shape[0]; ++i) {
      float out[2];
      policy.logits({obs.data<float>() + i * obs.shape[1], static_cast<size_t>(obs.shape[1])}, out);
      if (log_softmax) {
        const float top = std::max(out[0], out[1]);
        const float log_sum = top + std::log(std::exp(out[0] - top) + std::exp(out[1] - top));
        out[0] -= log_sum, out[1] -= log_sum;
      }
      for (int a = 0; a < 2; ++a)
        worst = std::max(worst, std::abs(out[a] - expected.data<float>()[i * 2 + a]));
    }
    CHECK(worst <= 1e-5f);
  }
}

TEST_CASE("VecNormalize statistics beside an SB3 model become env.normalize", "[sb3]") {
  const ModelFile model =
      read_sb3_model(case_dir("ppo_pendulum_vecnormalize") + "/model.zip", "Pendulum-v1");
  CHECK_THAT(model.config_yaml, Catch::Contains("normalize:") && Catch::Contains("0.98"));
  for (const char* key : {"wrappers/NormalizeObservation/mean", "wrappers/NormalizeObservation/var",
                          "wrappers/NormalizeObservation/count", "wrappers/NormalizeReward/var"})
    CHECK(model.wrapper_statistics.count(key) == 1);
  CHECK(model.wrapper_statistics.at("wrappers/NormalizeObservation/mean").shape ==
        std::vector<int64_t>{3});
  // Without the file beside it, the model has no statistics.
  CHECK(read_sb3_model(case_dir("ppo_pendulum") + "/model.zip", "Pendulum-v1")
            .wrapper_statistics.empty());
}

TEST_CASE("SB3 1.x files with gym's spaces and bounds play on Gymnasium's env", "[sb3][cli]") {
  // ppo_cartpole's weights with gym 0.21's CartPole space (velocities bounded by float32's
  // largest value, gym.spaces names, protocol 4): the same episodes as ppo_cartpole.
  const nlohmann::json returns = read_json(case_dir("ppo_cartpole") + "/returns.json");
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " eval --model " + case_dir("ppo_cartpole_gym_era") +
                  "/model.zip --env CartPole-v1 --episodes 1 --seed 0 2>&1");
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("3.40282e+38") && Catch::Contains("the same shape"));
  const double sb3 = returns["episode_returns"][0].get<double>();
  CHECK_THAT(r.output,
             Catch::Contains("mean_reward = " + std::to_string(static_cast<int>(sb3)) + ".00"));
}

TEST_CASE("an SB3 model file needs --env and says so", "[sb3][cli]") {
  const CommandResult r = run_command(std::string(RLRUN_BINARY) + " eval --model " +
                                      case_dir("ppo_cartpole") + "/model.zip 2>&1");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("SB3 model file") && Catch::Contains("--env"));
}

TEST_CASE("rlrun eval --trust takes an SB3 model file as it takes rlrun's", "[sb3][cli]") {
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " eval --model " + case_dir("ppo_cartpole") +
                  "/model.zip --env CartPole-v1 --trust --episodes 1 2>&1");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("PPO on CartPole-v1"));
}

TEST_CASE("an SB3 model file on an env of other spaces is refused", "[sb3][cli]") {
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " eval --model " + case_dir("ppo_cartpole") +
                  "/model.zip --env Pendulum-v1 2>&1");
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("trained on observations"));
}

TEST_CASE("SB3 files whose pickles would run code are refused and nothing runs",
          "[sb3][cli][security]") {
  // The fixtures' pickles run `touch /tmp/rlrun_pwned` when Python unpickles them.
  const std::string marker = "/tmp/rlrun_pwned";
  std::filesystem::remove(marker);
  for (const char* name : {"evil_os_system", "evil_torch"}) {
    INFO(name);
    const CommandResult r = run_command(std::string(RLRUN_BINARY) + " eval --model " +
                                        case_dir(name) + "/model.zip --env CartPole-v1 2>&1");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Catch::Contains("system") && Catch::Contains("does not read"));
  }
  CHECK_FALSE(std::filesystem::exists(marker));
}

TEST_CASE("an SB3 recurrent policy whose LSTM weights do not fit its hidden size is refused",
          "[sb3]") {
  // recurrent_ppo_cartpole with lstm_actor.weight_hh_l0 reshaped from [64, 16] to [1, 1024]:
  // read naively, a hidden size of 1024 (a 4096 x 1024 matrix per LSTM) from 4 KiB of weights.
  const std::string source = case_dir("recurrent_ppo_cartpole") + "/model.zip";
  const ZipReader original(source);
  ZipMembers members;
  for (const ZipEntry& entry : original.entries())
    members[entry.name] = original.read(entry, uint64_t{1} << 24);
  TensorMap tensors = read_torch_tensors(members["policy.pth"], "policy.pth", uint64_t{1} << 24);
  tensors["lstm_actor.weight_hh_l0"].shape = {1, 1024};
  std::vector<std::pair<std::string, const Tensor*>> ordered;
  for (const auto& [name, tensor] : tensors) ordered.emplace_back(name, &tensor);
  members["policy.pth"] = torch_save_state_dict(ordered);
  const std::string crafted =
      (std::filesystem::temp_directory_path() / "rlrun_sb3_bad_lstm.zip").string();
  write_zip_atomic(crafted, members);
  CHECK_THROWS_WITH(read_sb3_model(crafted, "CartPole-v1"),
                    Catch::Contains("lstm_actor.weight_hh_l0 is not 4*hidden x hidden"));
  std::filesystem::remove(crafted);
}

TEST_CASE("run.init_from fine-tunes an SB3 model file", "[sb3][cli]") {
  const std::string dir = std::filesystem::temp_directory_path() / "rlrun_sb3_init_from_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string sb3 = case_dir("ppo_cartpole") + "/model.zip";
  std::ofstream(dir + "/finetune.yaml")
      << "run: {name: finetune, seed: 1, total_timesteps: 256, out_dir: " << dir
      << ", init_from: " << sb3 << "}\n"
      << "env: {id: CartPole-v1}\n"
      << "algo: {id: PPO, n_steps: 128, batch_size: 64, n_epochs: 1}\n";  // SB3's default net
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " train " + dir + "/finetune.yaml 2>&1");
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.output,
             Catch::Contains("initialised from " + sb3 + " (PPO, CartPole-v1, 512 steps)"));
  // Another network than the file's is refused, naming the reason.
  std::ofstream(dir + "/other.yaml")
      << "run: {name: other, seed: 1, total_timesteps: 256, out_dir: " << dir
      << ", init_from: " << sb3 << "}\n"
      << "env: {id: CartPole-v1}\n"
      << "algo: {id: PPO, n_steps: 128, batch_size: 64, policy: {net_arch: [8]}}\n";
  const CommandResult other =
      run_command(std::string(RLRUN_BINARY) + " train " + dir + "/other.yaml 2>&1");
  CHECK(other.exit_code != 0);
  CHECK_THAT(other.output, Catch::Contains("cannot initialise from"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("rlrun eval --zoo-model plays an rl-zoo run folder", "[sb3][cli]") {
  // The layout rl_zoo3.train leaves: <algo>/<env>_<n>/<env>.zip, <env>/vecnormalize.pkl and
  // <env>/config.yml (the zoo's yaml.dump of an OrderedDict).
  const std::filesystem::path root =
      std::filesystem::temp_directory_path() / "rlrun_zoo_model_test";
  std::filesystem::remove_all(root);
  const std::filesystem::path folder = root / "ppo" / "Pendulum-v1_1";
  std::filesystem::create_directories(folder / "Pendulum-v1");
  const std::string source = case_dir("ppo_pendulum_vecnormalize");
  std::filesystem::copy_file(source + "/model.zip", folder / "Pendulum-v1.zip");
  std::filesystem::copy_file(source + "/vecnormalize.pkl",
                             folder / "Pendulum-v1" / "vecnormalize.pkl");
  const std::string eval = std::string(RLRUN_BINARY) + " eval --zoo-model " + folder.string() +
                           " --episodes 1 --seed 0 2>&1";
  // Without config.yml: SB3's episode (the statistics of vecnormalize.pkl frozen).
  const nlohmann::json returns = read_json(source + "/returns.json");
  const CommandResult plain = run_command(eval);
  CHECK(plain.exit_code == 0);
  CHECK_THAT(plain.output, Catch::Contains("PPO on Pendulum-v1"));
  const auto at = plain.output.find("mean_reward = ");
  REQUIRE(at != std::string::npos);
  CHECK(std::abs(std::stod(plain.output.substr(at + 14)) -
                 returns["episode_returns"][0].get<double>()) <= 0.006);
  // rl_zoo3.enjoy's --load-best and checkpoints: the same model under the zoo's other names,
  // with <env>/vecnormalize.pkl still found (the same return).
  std::filesystem::copy_file(source + "/model.zip", folder / "best_model.zip");
  std::filesystem::copy_file(source + "/model.zip", folder / "rl_model_2000_steps.zip");
  std::ofstream(folder / "rl_model_100_steps.zip") << "not a zip";
  for (const char* choice :
       {" --load-best", " --load-checkpoint 2000", " --load-last-checkpoint"}) {
    INFO(choice);
    const CommandResult chosen =
        run_command(std::string(RLRUN_BINARY) + " eval --zoo-model " + folder.string() + choice +
                    " --episodes 1 --seed 0 2>&1");
    REQUIRE(chosen.exit_code == 0);
    const std::string summary = plain.output.substr(at, plain.output.find('\n', at) - at);
    CHECK(chosen.output.find(summary) != std::string::npos);
  }
  const CommandResult missing = run_command(std::string(RLRUN_BINARY) + " eval --zoo-model " +
                                            folder.string() + " --load-checkpoint 7 2>&1");
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.output, Catch::Contains("no rl_model_7_steps.zip in it"));
  CHECK(run_command(std::string(RLRUN_BINARY) + " eval --load-best --env CartPole-v1 2>&1")
            .exit_code == 2);  // --load-best needs --zoo-model
  // config.yml's env_wrapper is applied as `rlrun zoo import` translates it; frame_stack is
  // named in a note.
  std::ofstream(folder / "Pendulum-v1" / "config.yml")
      << "!!python/object/apply:collections.OrderedDict\n"
      << "- - - env_wrapper\n"
      << "    - - gym.wrappers.TimeLimit:\n          max_episode_steps: 100\n"
      << "  - - frame_stack\n    - 2\n  - - policy\n    - MlpPolicy\n";
  const CommandResult wrapped = run_command(eval);
  CHECK(wrapped.exit_code == 0);
  CHECK_THAT(wrapped.output,
             Catch::Contains("mean_ep_length = 100.0") &&
                 Catch::Contains("sets frame_stack over VecNormalize's statistics"));
  // args.yml's env_kwargs (rl_zoo3.enjoy passes them to the env): Pendulum's g, a setting the
  // model's return shows; a keyword the env does not have is refused by name.
  std::filesystem::remove(folder / "Pendulum-v1" / "config.yml");
  std::ofstream(folder / "Pendulum-v1" / "args.yml")
      << "!!python/object/apply:collections.OrderedDict\n"
      << "- - - algo\n    - ppo\n  - - env_kwargs\n    - g: 2.0\n  - - seed\n    - 1\n";
  const CommandResult light = run_command(eval);
  CHECK(light.exit_code == 0);
  const auto light_at = light.output.find("mean_reward = ");
  REQUIRE(light_at != std::string::npos);
  CHECK(std::abs(std::stod(light.output.substr(light_at + 14)) -
                 returns["episode_returns"][0].get<double>()) > 1.0);
  std::ofstream(folder / "Pendulum-v1" / "args.yml")
      << "!!python/object/apply:collections.OrderedDict\n"
      << "- - - env_kwargs\n    - gravity_typo: 2.0\n";
  const CommandResult typo = run_command(eval);
  CHECK(typo.exit_code != 0);
  CHECK_THAT(typo.output, Catch::Contains("gravity_typo"));
  std::filesystem::remove(folder / "Pendulum-v1" / "args.yml");
  // A folder not named <env>_<n> is a usage error.
  const CommandResult wrong = run_command(std::string(RLRUN_BINARY) + " eval --zoo-model " +
                                          (root / "ppo").string() + " 2>&1");
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.output, Catch::Contains("<env>_<n>"));
  std::filesystem::remove_all(root);
}

TEST_CASE("rlrun eval --zoo-model stacks frames as the zoo's frame_stack", "[sb3][cli]") {
  // A model SB3 trained inside VecFrameStack(n_stack=2), in a run folder whose config.yml says
  // frame_stack: 2: rlrun plays SB3's episodes (zero padding after reset, oldest frame first).
  const std::filesystem::path root =
      std::filesystem::temp_directory_path() / "rlrun_zoo_frame_stack_test";
  std::filesystem::remove_all(root);
  const std::filesystem::path folder = root / "ppo" / "CartPole-v1_1";
  std::filesystem::create_directories(folder / "CartPole-v1");
  const std::string source = case_dir("ppo_cartpole_framestack");
  std::filesystem::copy_file(source + "/model.zip", folder / "CartPole-v1.zip");
  const std::string eval =
      std::string(RLRUN_BINARY) + " eval --zoo-model " + folder.string() + " --episodes 1 --seed ";
  // Without config.yml the env's observations do not fit the model's: refused.
  CHECK(run_command(eval + "0 2>&1").exit_code != 0);
  std::ofstream(folder / "CartPole-v1" / "config.yml")
      << "!!python/object/apply:collections.OrderedDict\n"
      << "- - - frame_stack\n    - 2\n  - - policy\n    - MlpPolicy\n";
  const nlohmann::json returns = read_json(source + "/returns.json");
  for (size_t i = 0; i < returns["seeds"].size(); ++i) {
    const int seed = returns["seeds"][i].get<int>();
    INFO("seed " << seed);
    const CommandResult r = run_command(eval + std::to_string(seed) + " 2>&1");
    REQUIRE(r.exit_code == 0);
    const auto at = r.output.find("mean_reward = ");
    REQUIRE(at != std::string::npos);
    CHECK(std::stod(r.output.substr(at + 14)) == returns["episode_returns"][i].get<double>());
  }
  std::filesystem::remove_all(root);
}

TEST_CASE("rlrun export reads SB3 model files", "[sb3][cli]") {
  const std::string dir = std::filesystem::temp_directory_path() / "rlrun_sb3_export_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const CommandResult r =
      run_command(std::string(RLRUN_BINARY) + " export --model " + case_dir("sac_pendulum") +
                  "/model.zip --env Pendulum-v1 " + "--format c --output " + dir + "/c 2>&1");
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir + "/c/policy.c"));
  std::filesystem::remove_all(dir);
}
