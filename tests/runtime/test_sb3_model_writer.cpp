// Writing SB3 model files (runtime/io/sb3/sb3_model_writer.hpp, `rlrun export --format sb3`),
// checked by reading them back with rlrun's SB3 reader against what the real SB3 2.4.1 did with
// the originals (tests/data/sb3/). That SB3 itself loads them and predicts the same is checked
// by tests/python/test_sb3_models.py where SB3 and torch are installed, and by
// scripts/data/check_sb3_export.sh.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/pickle_writer.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_writer.hpp"
#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/sb3_test_data.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

std::string case_dir(const std::string& name) { return sb3_case_dir(name); }
Tensor read_npy(const std::string& path) { return read_npy_file(path); }

std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

Space round_trip(const Space& space) {
  PickleWriter p(4);
  pickle_gymnasium_space(p, space);
  const std::vector<uint8_t> bytes = p.finish();
  const PickleDocument doc = read_pickle(bytes.data(), bytes.size(), "space", is_sb3_space_global);
  return sb3_space(doc.root(), "space");
}

double mean_reward(const std::string& output) {
  const auto at = output.find("mean_reward = ");
  REQUIRE(at != std::string::npos);
  return std::stod(output.substr(at + 14));
}

}  // namespace

TEST_CASE("Gymnasium spaces pickled for SB3 read back as the same spaces", "[sb3]") {
  const Space spaces[] = {
      Space::box({-4.8f, -INFINITY, -0.41887903f, -INFINITY},
                 {4.8f, INFINITY, 0.41887903f, INFINITY}),
      Space::box(-2.0f, 2.0f, {2, 3}),
      Space::box(0.0f, 255.0f, {4, 3, 2}, BoxDtype::kUint8),
      Space::discrete(5, 2),
      Space::multi_discrete({3, 4, 2}),
      Space::multi_binary(6),
      Space::dict({{"position", Space::box(-1.0f, 1.0f, {3})}, {"mode", Space::discrete(3)}}),
  };
  for (const Space& space : spaces) {
    INFO(space.describe());
    CHECK(round_trip(space) == space);
  }
}

TEST_CASE("image spaces transpose as SB3's VecTransposeImage does", "[sb3]") {
  // An (H, W, C) = (2, 3, 4) image whose bounds number the elements in row-major order:
  // numpy's transpose(2, 0, 1) puts element (y, x, c) at (c, y, x).
  std::vector<float> low(24), high(24);
  for (int i = 0; i < 24; ++i) low[i] = static_cast<float>(i), high[i] = 255.0f;
  const Space hwc = Space::box(low, high, {2, 3, 4}, BoxDtype::kUint8);
  const Space chw = channels_first_image(hwc);
  REQUIRE(chw.shape() == std::vector<int>{4, 2, 3});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 4; ++c)
        CHECK(chw.low()[(c * 2 + y) * 3 + x] == hwc.low()[(y * 3 + x) * 4 + c]);
  CHECK(chw.dtype() == BoxDtype::kUint8);
  CHECK(channels_last_image(chw) == hwc);
}

TEST_CASE("SB3 model files written by rlrun read back as the files SB3 wrote", "[sb3]") {
  // Each of SB3's own files, read, written back and read again: the same tensors under the
  // same names, the same algorithm, and SB3's deterministic actions on its observations.
  struct Case {
    const char* name;
    const char* env_id;
  };
  const Case cases[] = {{"ppo_cartpole", "CartPole-v1"},
                        {"a2c_cartpole", "CartPole-v1"},
                        {"dqn_cartpole", "CartPole-v1"},
                        {"ppo_pendulum", "Pendulum-v1"},
                        {"sac_pendulum", "Pendulum-v1"},
                        {"td3_pendulum", "Pendulum-v1"},
                        {"ddpg_pendulum", "Pendulum-v1"},
                        {"ppo_sde_pendulum", "Pendulum-v1"},
                        {"sac_sde_pendulum", "Pendulum-v1"},
                        // sb3-contrib's
                        {"qrdqn_cartpole", "CartPole-v1"},
                        {"tqc_pendulum", "Pendulum-v1"},
                        {"trpo_pendulum", "Pendulum-v1"},
                        {"maskable_ppo_cartpole", "CartPole-v1"},
                        {"recurrent_ppo_cartpole", "CartPole-v1"},
                        {"recurrent_ppo_pendulum", "Pendulum-v1"}};
  const std::filesystem::path dir = fresh_dir("rlrun_sb3_writer_test");
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string original = case_dir(c.name) + "/model.zip";
    const LoadedModel model =
        load_model(original, builtin_registry(), {std::string("env.id=") + c.env_id}, {},
                   ModelEnv::kSpacesOnly);
    const Sb3ModelExport sb3 = sb3_model_export(model);
    for (const char* member : {"data", "policy.pth", "pytorch_variables.pth",
                               "_stable_baselines3_version", "system_info.txt"})
      CHECK(sb3.members.count(member) == 1);
    const std::string written = (dir / (std::string(c.name) + ".zip")).string();
    write_zip_atomic(written, sb3.members);
    REQUIRE(is_sb3_model_file(written));
    const ModelFile before = read_sb3_model(original, c.env_id);
    const ModelFile after = read_sb3_model(written, c.env_id);
    CHECK(after.meta.algorithm == before.meta.algorithm);
    CHECK(after.meta.observation_space == before.meta.observation_space);
    CHECK(after.meta.action_space == before.meta.action_space);
    CHECK(after.meta.num_timesteps == before.meta.num_timesteps);
    // The same networks (config.yaml may also spell out defaults the original left implicit).
    for (const char* line : {"net_arch:", "activation_fn:", "lstm_hidden_size:"})
      CHECK((before.config_yaml.find(line) == std::string::npos) ==
            (after.config_yaml.find(line) == std::string::npos));
    REQUIRE(after.tensors.size() == before.tensors.size());
    for (const auto& [name, tensor] : before.tensors) {
      INFO(name);
      REQUIRE(after.tensors.count(name) == 1);
      CHECK(after.tensors.at(name).shape == tensor.shape);
      CHECK(after.tensors.at(name).bytes == tensor.bytes);
    }
    // The written file plays: SB3's actions on SB3's observations.
    LoadedModel again =
        load_model(written, builtin_registry(), {std::string("env.id=") + c.env_id});
    const Tensor obs = read_npy(case_dir(c.name) + "/observations.npy");
    const Eigen::MatrixXf observations =
        Eigen::Map<const Eigen::MatrixXf>(obs.data<float>(), obs.shape[1], obs.shape[0]);
    Eigen::MatrixXf actions;
    again.algorithm->predict(observations, true, actions);
    const Tensor expected = read_npy(case_dir(c.name) + "/actions.npy");
    if (expected.dtype == DType::kInt64) {
      for (int i = 0; i < actions.cols(); ++i)
        REQUIRE(static_cast<int64_t>(actions(0, i)) == expected.data<int64_t>()[i]);
    } else {
      const Eigen::Map<const Eigen::MatrixXf> sb3_actions(expected.data<float>(), actions.rows(),
                                                          actions.cols());
      CHECK((actions - sb3_actions).cwiseAbs().maxCoeff() <= 1e-5f);
    }
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("SB3 CnnPolicy files written by rlrun read back as the file SB3 wrote", "[sb3]") {
  // PPO's CnnPolicy: ActorCriticCnnPolicy, the channels-first space SB3 keeps, the shared
  // NatureCNN under its three names, one optimizer param per unique tensor. (SB3 itself loads
  // such files and predicts the same: scripts/data/check_sb3_export.sh.)
  const std::string original = case_dir("ppo_cnn_gripper_pixels") + "/model.zip";
  const std::vector<std::string> env = {"env.id=GripperLift-v0", "env.kwargs.obs_type=pixels",
                                        "env.kwargs.image_size=36"};
  const LoadedModel model =
      load_model(original, builtin_registry(), env, {}, ModelEnv::kSpacesOnly);
  const Sb3ModelExport sb3 = sb3_model_export(model);
  const std::vector<uint8_t>& pth = sb3.members.at("policy.pth");
  const std::string text(pth.begin(), pth.end());
  for (const char* name : {"features_extractor.cnn.0.weight", "pi_features_extractor.cnn.0.weight",
                           "vf_features_extractor.linear.0.bias"})
    CHECK(text.find(name) != std::string::npos);
  // (read_sb3_model below takes these tensors only from an ActorCriticCnnPolicy.)
  const std::filesystem::path dir = fresh_dir("rlrun_sb3_cnn_writer_test");
  const std::string written = (dir / "cnn.zip").string();
  write_zip_atomic(written, sb3.members);
  const ModelFile before = read_sb3_model(original, "GripperLift-v0");
  const ModelFile after = read_sb3_model(written, "GripperLift-v0");
  CHECK(after.meta.observation_space == before.meta.observation_space);
  CHECK(after.meta.algorithm == "PPO");
  REQUIRE(after.tensors.size() == before.tensors.size());
  for (const auto& [name, tensor] : before.tensors) {
    INFO(name);
    REQUIRE(after.tensors.count(name) == 1);
    CHECK(after.tensors.at(name).bytes == tensor.bytes);
  }
  CHECK(after.config_yaml.find("features_dim: 64") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("SB3 off-policy CnnPolicy files written by rlrun read back as the file SB3 wrote",
          "[sb3]") {
  // DQN's and SAC's CnnPolicy (dqn/sac policies.py CnnPolicy): every network's own NatureCNN
  // under SB3's names (DQN's q_net.features_extractor beside q_net.q_net), the features_dim in
  // policy_kwargs; SAC's critic optimizer holds the critic's extractor (not shared).
  const std::string pixels =
      "env.wrappers=[{id: AddRenderObservation, width: 36, height: 36}, "
      "{id: GrayscaleObservation, keep_dim: true}]";
  const std::filesystem::path dir = fresh_dir("rlrun_sb3_cnn_off_policy_writer_test");
  for (const auto& [name, env, policy_class] :
       {std::tuple{"dqn_cnn_cartpole_pixels", "CartPole-v1", "stable_baselines3.dqn.policies"},
        std::tuple{"sac_cnn_pendulum_pixels", "Pendulum-v1", "stable_baselines3.sac.policies"}}) {
    INFO(name);
    const std::string original = case_dir(name) + "/model.zip";
    const LoadedModel model =
        load_model(original, builtin_registry(), {std::string("env.id=") + env, pixels}, {},
                   ModelEnv::kSpacesOnly);
    const Sb3ModelExport sb3 = sb3_model_export(model);
    const std::vector<uint8_t>& data = sb3.members.at("data");
    const std::string data_text(data.begin(), data.end());
    CHECK(data_text.find(policy_class) != std::string::npos);
    CHECK(data_text.find("\"features_dim\": 16") != std::string::npos);
    const std::vector<uint8_t>& pth = sb3.members.at("policy.pth");
    const std::string text(pth.begin(), pth.end());
    if (std::string(name).starts_with("dqn")) {
      CHECK(text.find("q_net.features_extractor.cnn.0.weight") != std::string::npos);
      CHECK(text.find("q_net.q_net.0.weight") != std::string::npos);
      CHECK(text.find("q_net.q_net.features_extractor") == std::string::npos);
    }
    const std::string written = (dir / (std::string(name) + ".zip")).string();
    write_zip_atomic(written, sb3.members);
    const ModelFile before = read_sb3_model(original, env);
    const ModelFile after = read_sb3_model(written, env);
    CHECK(after.meta.observation_space == before.meta.observation_space);
    CHECK(after.meta.algorithm == before.meta.algorithm);
    REQUIRE(after.tensors.size() == before.tensors.size());
    for (const auto& [tensor_name, tensor] : before.tensors) {
      INFO(tensor_name);
      REQUIRE(after.tensors.count(tensor_name) == 1);
      CHECK(after.tensors.at(tensor_name).bytes == tensor.bytes);
    }
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("rlrun export --format sb3 of an rlrun-trained model plays as the model", "[sb3][cli]") {
  // PPO with a linear learning-rate schedule and a non-default network, SAC with its learned
  // entropy coefficient, DQN: trained briefly by rlrun, exported, and evaluated from the SB3
  // file on the same seeds.
  const std::filesystem::path dir = fresh_dir("rlrun_sb3_export_trained_test");
  struct Case {
    const char* name;
    const char* env;
    const char* algo;
  };
  const Case cases[] = {
      {"ppo", "CartPole-v1",
       "{id: PPO, n_steps: 128, batch_size: 64, n_epochs: 2, learning_rate: lin_0.001, "
       "policy: {net_arch: {pi: [16], vf: [8, 8]}, activation_fn: relu}}"},
      {"sac", "Pendulum-v1",
       "{id: SAC, learning_starts: 64, batch_size: 32, train_freq: [2, step], "
       "policy: {net_arch: [16, 16]}}"},
      {"dqn", "CartPole-v1",
       "{id: DQN, learning_starts: 64, batch_size: 32, policy: {net_arch: [16]}}"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string config = (dir / (std::string(c.name) + ".yaml")).string();
    std::ofstream(config) << "run: {name: " << c.name
                          << ", seed: 1, total_timesteps: 256, out_dir: " << dir.string()
                          << "}\nenv: {id: " << c.env << "}\nalgo: " << c.algo << "\n";
    const CommandResult train =
        run_command(std::string(RLRUN_BINARY) + " train " + config + " 2>&1");
    REQUIRE(train.exit_code == 0);
    const std::string model = (dir / c.name / "seed1" / "model.zip").string();
    REQUIRE(std::filesystem::exists(model));
    const std::string sb3 = (dir / (std::string(c.name) + "_sb3.zip")).string();
    const CommandResult exported = run_command(std::string(RLRUN_BINARY) + " export --model " +
                                               model + " --format sb3 --output " + sb3 + " 2>&1");
    REQUIRE(exported.exit_code == 0);
    CHECK_THAT(exported.output, Catch::Contains("a Stable-Baselines3 2.4.1 model file"));
    REQUIRE(is_sb3_model_file(sb3));
    const std::string eval = " --episodes 2 --seed 3 2>&1";
    const CommandResult mine =
        run_command(std::string(RLRUN_BINARY) + " eval --model " + model + eval);
    const CommandResult theirs =
        run_command(std::string(RLRUN_BINARY) + " eval --model " + sb3 + " --env " + c.env + eval);
    REQUIRE(mine.exit_code == 0);
    REQUIRE(theirs.exit_code == 0);
    CHECK(mean_reward(mine.output) == mean_reward(theirs.output));
    if (std::string(c.name) == "ppo")
      CHECK_THAT(exported.output, Catch::Contains("learning_rate 'lin_0.001' is written as its "
                                                  "initial value"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("rlrun export --format sb3 refuses what SB3 has no class for", "[sb3][cli]") {
  // ARS: neither SB3 nor sb3-contrib's algorithms written here have a file for it.
  const std::filesystem::path dir = fresh_dir("rlrun_sb3_export_refused_test");
  const std::string config = (dir / "ars.yaml").string();
  std::ofstream(config) << "run: {name: ars, seed: 1, total_timesteps: 64, out_dir: "
                        << dir.string()
                        << "}\nenv: {id: CartPole-v1}\nalgo: {id: ARS, n_delta: 2}\n";
  REQUIRE(run_command(std::string(RLRUN_BINARY) + " train " + config + " 2>&1").exit_code == 0);
  const std::string output = (dir / "out.zip").string();
  const CommandResult r = run_command(std::string(RLRUN_BINARY) + " export --model " +
                                      (dir / "ars" / "seed1" / "model.zip").string() +
                                      " --format sb3 --output " + output + " 2>&1");
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("is not one of SB3's (PPO, A2C, DQN, SAC, TD3, DDPG)"));
  CHECK_FALSE(std::filesystem::exists(output));
  std::filesystem::remove_all(dir);
}
