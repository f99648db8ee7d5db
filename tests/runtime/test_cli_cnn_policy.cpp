// SB3's CnnPolicy in PPO and A2C (features_extractor_class: NatureCNN) from the command line, on
// CartPole seen through its own rendering (AddRenderObservation, GrayscaleObservation,
// FrameStack: four 40x40 gray frames, channels first): it trains, saves torch's tensors, reloads
// for eval, gives the same model on 1 and 2 threads, and a CNN on a vector observation is
// refused with SB3's reason. The zoo's `policy: CnnPolicy` imports to the same settings.
#include <catch2/catch.hpp>
#include <fstream>

#include "runtime/cli_runner.hpp"
#include "runtime/same_tensors.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

std::string write_config(const TempDir& dir, const std::string& name, const std::string& algo,
                         const std::string& wrappers) {
  const std::string path = dir / (name + ".yaml");
  std::ofstream(path) << "run: {name: " << name
                      << ", seed: 3, total_timesteps: 256, out_dir: " << dir.str() << "/runs}\n"
                      << "env:\n  id: CartPole-v1\n  n_envs: 2\n  wrappers: " << wrappers << "\n"
                      << "algo: {id: " << algo
                      << ", n_steps: 64, policy: {features_extractor_class: NatureCNN, "
                         "features_dim: 64, net_arch: []}}\n";
  return path;
}

const char* kPixels =
    "[{id: AddRenderObservation, width: 40, height: 40}, {id: GrayscaleObservation}, "
    "{id: FrameStack, n_stack: 4}]";

}  // namespace

TEST_CASE("cli: PPO and A2C train a NatureCNN on pixels, the same on 1 and 2 threads",
          "[cli][cnn]") {
  TempDir dir("cnn_policy");
  for (const char* algo : {"PPO", "A2C"}) {
    INFO(algo);
    const std::string name = std::string("pixels_") + algo;
    const std::string config = write_config(dir, name, algo, kPixels);
    const std::string model = dir / ("runs/" + name + "/seed3/model.zip");
    const auto one = run_rlrun("--threads 1 train " + config);
    INFO(one.output);
    REQUIRE(one.exit_code == 0);
    const std::string first = dir / (name + "_1.zip");
    std::filesystem::copy_file(model, first);
    const auto two = run_rlrun("--threads 2 train " + config);
    REQUIRE(two.exit_code == 0);
    check_same_tensors(first, model);
    const auto eval = run_rlrun("eval --model " + model + " --episodes 2");
    INFO(eval.output);
    CHECK(eval.exit_code == 0);
  }
  // The tensors are torch's: SB3's names and shapes for a 4x40x40 channels-first image
  // (40 -> 9 -> 3 -> 1 pixels through the three convolutions).
  const ModelFile model = read_model(dir / "runs/pixels_PPO/seed3/model.zip");
  CHECK(model.tensors.at("features_extractor.cnn.0.weight").shape ==
        std::vector<int64_t>{32, 4, 8, 8});
  CHECK(model.tensors.at("features_extractor.cnn.4.weight").shape ==
        std::vector<int64_t>{64, 64, 3, 3});
  CHECK(model.tensors.at("features_extractor.linear.0.weight").shape ==
        std::vector<int64_t>{64, 64});
  CHECK(model.tensors.at("action_net.weight").shape == std::vector<int64_t>{2, 64});
}

TEST_CASE("cli: a NatureCNN on a vector observation is refused with SB3's reason", "[cli][cnn]") {
  TempDir dir("cnn_refused");
  const std::string config = write_config(dir, "vector", "PPO", "[]");
  const auto r = run_rlrun("train " + config);
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("features_extractor_class") &&
                           Catch::Contains("you should use NatureCNN only with images") &&
                           Catch::Contains("Box([-4.8"));
}

TEST_CASE("cli: a NatureCNN whose batch of activations cannot fit is refused before allocating",
          "[cli][cnn]") {
  // 2048x2048 RGB frames: the CNN's weights (features_dim 8) fit, but a batch of 1 024 images
  // keeps ~29 M floats of layer outputs each, twice (forward and backward): ~240 GB.
  TempDir dir("cnn_too_big");
  const std::string config = dir / "big.yaml";
  std::ofstream(config)
      << "run: {name: big, seed: 1, total_timesteps: 2000, out_dir: " << dir.str() << "/runs}\n"
      << "env:\n  id: CartPole-v1\n  wrappers: [{id: AddRenderObservation, "
         "width: 2048, height: 2048}]\n"
      << "algo: {id: DQN, batch_size: 1024, policy: "
         "{features_extractor_class: NatureCNN, features_dim: 8, net_arch: []}}\n";
  const auto r = run_rlrun("train " + config);
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK_THAT(r.output, Catch::Contains("big.yaml:5") &&
                           Catch::Contains("activations of a batch of 1024 images"));
}

TEST_CASE("cli: SB3's Atari preprocessing on pixel CartPole, resumed exactly", "[cli][cnn]") {
  // WarpFrame's pieces (OpenCV gray, INTER_AREA to 44x44), MaxAndSkip, NoopReset, the sign of
  // the reward, and VecFrameStack's layout: four frames on the channel axis, (44, 44, 4).
  TempDir dir("cnn_atari_pieces");
  const std::string wrappers =
      "[{id: AddRenderObservation, width: 90, height: 60}, "
      "{id: GrayscaleObservation, keep_dim: true, weights: opencv}, "
      "{id: ResizeObservation, shape: 44}, {id: MaxAndSkip, skip: 2}, "
      "{id: NoopReset, noop_max: 4}, {id: TransformReward, sign: true}, "
      "{id: FrameStack, n_stack: 4, layout: sb3}]";
  const std::string config = write_config(dir, "atari_pieces", "PPO", wrappers);
  const auto full = run_rlrun("train " + config);
  INFO(full.output);
  REQUIRE(full.exit_code == 0);
  const std::string run = dir / "runs/atari_pieces/seed3";
  const ModelFile model = read_model(run + "/model.zip");
  // Channels last: SB3 would transpose (44, 44, 4) to (4, 44, 44); the first conv sees 4.
  CHECK(model.tensors.at("features_extractor.cnn.0.weight").shape ==
        std::vector<int64_t>{32, 4, 8, 8});
  const std::string uninterrupted = dir / "uninterrupted.zip";
  std::filesystem::copy_file(run + "/model.zip", uninterrupted);
  // Stopped after the first rollout and resumed: the wrappers' state (the max-pool buffer, the
  // no-op generator, the stacks) comes back with the checkpoint.
  std::filesystem::remove_all(dir / "runs");
  const auto half =
      run_rlrun("train " + config + " --set run.total_timesteps=128 --set checkpoint.freq=128");
  INFO(half.output);
  REQUIRE(half.exit_code == 0);
  const auto resumed = run_rlrun("train --resume " + run + " --set run.total_timesteps=256");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  check_same_tensors(uninterrupted, run + "/model.zip");
  const auto eval = run_rlrun("eval --model " + run + "/model.zip --episodes 2");
  CHECK(eval.exit_code == 0);
}

TEST_CASE("cli: DQN trains a NatureCNN on stacked frames, the same on 1 and 2 threads",
          "[cli][cnn]") {
  TempDir dir("cnn_dqn");
  const std::string config = dir / "pixels_dqn.yaml";
  std::ofstream(config)
      << "run: {name: pixels_dqn, seed: 3, total_timesteps: 600, out_dir: " << dir.str()
      << "/runs}\n"
      << "env:\n  id: CartPole-v1\n  n_envs: 2\n  wrappers: "
      << "[{id: AddRenderObservation, width: 60, height: 40}, "
         "{id: GrayscaleObservation, keep_dim: true}, {id: ResizeObservation, shape: 36}, "
         "{id: FrameStack, n_stack: 4, layout: sb3}]\n"
      << "algo: {id: DQN, learning_starts: 200, buffer_size: 1000, batch_size: 32, "
         "target_update_interval: 100, policy: {features_extractor_class: NatureCNN, "
         "features_dim: 32, net_arch: []}}\n";
  const std::string model = dir / "runs/pixels_dqn/seed3/model.zip";
  const auto one = run_rlrun("--threads 1 train " + config);
  INFO(one.output);
  REQUIRE(one.exit_code == 0);
  const std::string first = dir / "one_thread.zip";
  std::filesystem::copy_file(model, first);
  const auto two = run_rlrun("--threads 2 train " + config);
  REQUIRE(two.exit_code == 0);
  check_same_tensors(first, model);
  const ModelFile file = read_model(model);
  CHECK(file.tensors.at("q_net.features_extractor.cnn.0.weight").shape ==
        std::vector<int64_t>{32, 4, 8, 8});
  CHECK(file.tensors.at("q_net.0.weight").shape == std::vector<int64_t>{2, 32});
  // The target network has an extractor of its own (SB3 make_q_net).
  CHECK(file.tensors.at("q_net_target.features_extractor.linear.0.weight").numel() == 32 * 64);
  const auto eval = run_rlrun("eval --model " + model + " --episodes 2");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  // The export starts at what the Q-network reads: FrameStack's (36, 36, 4) observations.
  const auto exported =
      run_rlrun("export --model " + model + " --format onnx --output " + dir / "m.onnx");
  INFO(exported.output);
  CHECK(exported.exit_code == 0);
  CHECK_THAT(exported.output, Catch::Contains("reads the observations of the wrapper FrameStack") &&
                                  Catch::Contains("obs [batch, 5184]"));
}

TEST_CASE(
    "cli: SAC, TQC, TD3 and DDPG train their actor's and critic's NatureCNN on pixels, the same "
    "on 1 and 2 threads",
    "[cli][cnn]") {
  TempDir dir("cnn_off_policy");
  for (const std::string algo : {"SAC", "TQC", "TD3", "DDPG"}) {
    INFO(algo);
    const std::string config = dir / (algo + ".yaml");
    std::ofstream(config)
        << "run: {name: " << algo << ", seed: 5, total_timesteps: 500, out_dir: " << dir.str()
        << "/runs}\n"
        << "env:\n  id: Pendulum-v1\n  n_envs: 2\n  wrappers: "
        << "[{id: AddRenderObservation, width: 36, height: 36}, "
           "{id: GrayscaleObservation, keep_dim: true}, {id: FrameStack, n_stack: 2, layout: "
           "sb3}]\n"
        << "algo: {id: " << algo
        << ", learning_starts: 200, buffer_size: 1000, batch_size: 16, "
           "policy: {features_extractor_class: NatureCNN, features_dim: 16, net_arch: [32]}}\n";
    const std::string model = dir / ("runs/" + algo + "/seed5/model.zip");
    const auto one = run_rlrun("--threads 1 train " + config);
    INFO(one.output);
    REQUIRE(one.exit_code == 0);
    const std::string first = dir / (algo + "_one_thread.zip");
    std::filesystem::copy_file(model, first);
    const auto two = run_rlrun("--threads 2 train " + config);
    REQUIRE(two.exit_code == 0);
    check_same_tensors(first, model);
    // SB3's names: one NatureCNN each for the actor and the critic (and their targets), the
    // frames (36, 36, 2) read channels-last.
    const ModelFile file = read_model(model);
    for (const std::string module : {"actor", "critic", "critic_target"})
      CHECK(file.tensors.at(module + ".features_extractor.cnn.0.weight").shape ==
            std::vector<int64_t>{32, 2, 8, 8});
    CHECK(file.tensors.count("actor_target.features_extractor.linear.0.bias") ==
          (algo == "TD3" || algo == "DDPG" ? 1u : 0u));
    CHECK(file.tensors.at("critic.qf0.0.weight").shape == std::vector<int64_t>{32, 16 + 1});
    const auto eval = run_rlrun("eval --model " + model + " --episodes 1");
    INFO(eval.output);
    CHECK(eval.exit_code == 0);
  }
}

TEST_CASE(
    "cli: CombinedExtractor (MultiInputPolicy) on a frame and the state: PPO, DQN and SAC train, "
    "save SB3's names and export from the Dict",
    "[cli][cnn][combined]") {
  TempDir dir("cnn_combined");
  struct Run {
    std::string algo, env, settings;
  };
  for (const Run& r : {Run{"PPO", "CartPole-v1", "n_steps: 64, batch_size: 32, n_epochs: 1"},
                       Run{"DQN", "CartPole-v1",
                           "learning_starts: 100, buffer_size: 500, "
                           "batch_size: 16"},
                       Run{"SAC", "Pendulum-v1",
                           "learning_starts: 100, buffer_size: 500, "
                           "batch_size: 16"}}) {
    INFO(r.algo);
    const std::string config = dir / (r.algo + ".yaml");
    std::ofstream(config)
        << "run: {name: " << r.algo << ", seed: 2, total_timesteps: 256, out_dir: " << dir.str()
        << "/runs}\n"
        << "env: {id: " << r.env
        << ", wrappers: [{id: AddRenderObservation, width: 36, height: 36, render_only: false}]}\n"
        << "algo: {id: " << r.algo << ", " << r.settings
        << ", policy: {features_extractor_class: MultiInputPolicy, cnn_output_dim: 16, net_arch: "
           "[32]}}\n";
    const auto train = run_rlrun("--threads 2 train " + config);
    INFO(train.output);
    REQUIRE(train.exit_code == 0);
    const std::string model = dir / ("runs/" + r.algo + "/seed2/model.zip");
    const ModelFile file = read_model(model);
    const std::string module = r.algo == "PPO"   ? "features_extractor"
                               : r.algo == "DQN" ? "q_net.features_extractor"
                                                 : "critic.features_extractor";
    CHECK(file.tensors.at(module + ".extractors.pixels.cnn.0.weight").shape ==
          std::vector<int64_t>{32, 3, 8, 8});
    CHECK(file.tensors.count(module + ".extractors.state.cnn.0.weight") == 0);
    // The graph starts at AddRenderObservation's Dict: the frame and the state as inputs.
    const auto exported =
        run_rlrun("export --model " + model + " --output " + dir / (r.algo + ".onnx"));
    INFO(exported.output);
    CHECK(exported.exit_code == 0);
    CHECK_THAT(exported.output, Catch::Contains("inputs pixels [batch, 3888], state") &&
                                    Catch::Contains("AddRenderObservation"));
  }
}

TEST_CASE(
    "cli: PPO with share_features_extractor false trains two CNNs, the same on 1 and 2 "
    "threads",
    "[cli][cnn]") {
  TempDir dir("cnn_separate");
  const std::string config = dir / "separate.yaml";
  std::ofstream(config) << "run: {name: separate, seed: 4, total_timesteps: 256, out_dir: "
                        << dir.str() << "/runs}\n"
                        << "env:\n  id: CartPole-v1\n  n_envs: 2\n  wrappers: " << kPixels << "\n"
                        << "algo: {id: PPO, n_steps: 64, batch_size: 32, policy: "
                           "{features_extractor_class: NatureCNN, features_dim: 32, net_arch: [], "
                           "share_features_extractor: false}}\n";
  const std::string model = dir / "runs/separate/seed4/model.zip";
  const auto one = run_rlrun("--threads 1 train " + config);
  INFO(one.output);
  REQUIRE(one.exit_code == 0);
  const std::string first = dir / "one.zip";
  std::filesystem::copy_file(model, first);
  REQUIRE(run_rlrun("--threads 2 train " + config).exit_code == 0);
  check_same_tensors(first, model);
  const ModelFile file = read_model(model);
  CHECK(file.tensors.at("pi_features_extractor.cnn.0.weight").shape ==
        std::vector<int64_t>{32, 4, 8, 8});
  CHECK(file.tensors.count("vf_features_extractor.cnn.0.weight") == 1);
  CHECK(run_rlrun("eval --model " + model + " --episodes 1").exit_code == 0);
}
