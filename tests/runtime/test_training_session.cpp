// TrainingSession (runtime/run/trainer.hpp): SB3's model.learn() called again continues the same
// training — learn(256) then learn(to 768) ends with the weights of one learn(768) — and the
// caller's callbacks see every step and can stop it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;

namespace training_session_test {

const char* const kPpo =
    "env: {id: CartPole-v1, n_envs: 2}\n"
    "algo: {id: PPO, n_steps: 64, batch_size: 64, n_epochs: 2, policy: {net_arch: [16]}}\n";
const char* const kSac =
    "env: {id: Pendulum-v1, n_envs: 2}\n"
    "algo: {id: SAC, learning_starts: 100, batch_size: 32, buffer_size: 1000, "
    "policy: {net_arch: [16]}}\n";

Experiment experiment(const std::string& out_dir, const std::string& name,
                      const char* settings = kPpo) {
  const std::string yaml = "run: {name: " + name +
                           ", seed: 5, total_timesteps: 768, out_dir: " + out_dir +
                           ", verbose: 0}\n" + settings;
  return parse_experiment(ConfigNode::load_string(yaml, name + ".yaml"), builtin_registry());
}

TensorMap final_tensors(const TrainOutcome& outcome) {
  return read_model(outcome.model_path).tensors;
}

class CountingCallback : public Callback {
 public:
  explicit CountingCallback(int64_t stop_at) : stop_at_(stop_at) {}
  bool on_step(int64_t num_timesteps) override {
    ++calls;
    last = num_timesteps;
    return num_timesteps < stop_at_;
  }
  void at_safe_point(int64_t) override { ++safe_points; }
  int calls = 0, safe_points = 0;
  int64_t last = 0;

 private:
  int64_t stop_at_;
};

}  // namespace training_session_test

using namespace training_session_test;

TEST_CASE("A training session's learn() continues where the last one stopped",
          "[runtime][training_session]") {
  const char* settings = GENERATE(kPpo, kSac);
  testing::TempDir dir("training_session");
  TrainOutcome whole = train_experiment(experiment(dir.str(), "whole", settings),
                                        builtin_registry(), testing::test_execution());
  REQUIRE(whole.timesteps == 768);

  TrainingSession session(experiment(dir.str(), "parts", settings), builtin_registry(),
                          testing::test_execution());
  CHECK(session.learn(0).timesteps == 0);  // builds the policy: model.zip of the initial weights
  CHECK(session.learn(256).timesteps == 256);
  const TrainOutcome parts = session.learn(768);
  CHECK(parts.start_timesteps == 256);
  CHECK(parts.timesteps == 768);
  const TensorMap a = final_tensors(whole), b = final_tensors(parts);
  REQUIRE(a.size() == b.size());
  for (const auto& [name, tensor] : a) {
    INFO(name);
    CHECK(tensor.bytes == b.at(name).bytes);
  }
}

TEST_CASE("A training session's extra callbacks see every step and can stop it",
          "[runtime][training_session]") {
  testing::TempDir dir("training_session_callbacks");
  TrainingSession session(experiment(dir.str(), "callbacks"), builtin_registry(),
                          testing::test_execution());
  std::vector<std::unique_ptr<Callback>> extra;
  extra.push_back(std::make_unique<CountingCallback>(300));
  const auto& counter = static_cast<const CountingCallback&>(*extra.front());
  const TrainOutcome outcome = session.learn(768, extra);
  CHECK(counter.calls == 150);  // 2 envs: 300 steps in 150 VecEnv steps
  CHECK(counter.last == 300);
  CHECK(counter.safe_points == 2);  // after the rollouts of 128 and 256 steps
  CHECK(outcome.timesteps == 300);
  CHECK(session.learn(400).timesteps >= 400);  // without it, training goes on
}
