// `--trust` (issue 41): a model trained on one's own Python env (or scenario) evaluates,
// records and exports without a --set per value it names: rlrun prints what it will run, on
// stderr, then runs it. Without --trust the refusal names both ways to vouch (docs/security.md,
// "Vouching for a value").
#include <catch2/catch.hpp>

#include <filesystem>

#include "envs/python_env_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kCartPolePort = "python:rlrun_test_envs.cartpole:CartPolePort";

// `rlrun ARGS` as run_rlrun_python, with stderr alone on the output (stdout dropped).
CommandResult stderr_of(const std::string& args) {
  return run_command("(cd " + kSourceDir + " && PYTHONPATH=" + kSourceDir + "/tests/python_envs " +
                     RLRUN_BINARY + " " + args + " 2>&1 >/dev/null)");
}

}  // namespace

TEST_CASE(
    "trust: --trust evaluates a Python env's model (and records it) after saying what "
    "runs, and export runs nothing, so it needs no trust",
    "[cli][python][security]") {
  TempDir dir("trust_python");
  const auto trained = run_rlrun_python(
      "train " + python_experiment(dir.str(), "port", kCartPolePort,
                                   "id: PPO, n_steps: 64, batch_size: 64, n_epochs: 1", 64));
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  const std::string model = dir / "runs/port/seed1/model.zip";
  const std::string origin = model + ":config.yaml";

  // Refused: eval and record, which build the env, each name --set and --trust.
  for (const std::string& command :
       {"eval --model " + model + " --episodes 1",
        "record --model " + model + " --frames " + dir / "refused_frames"}) {
    const auto refused = run_rlrun_python(command);
    INFO(command << "\n" << refused.output);
    CHECK(refused.exit_code == 2);
    CHECK(refused.output.find("--set env.python=" + kPython) != std::string::npos);
    CHECK(refused.output.find("Or pass --trust to accept everything " + origin) !=
          std::string::npos);
  }

  // --trust: what will run is on stderr, one line per value, then it runs.
  const std::string announced_id = "trusting " + origin + " (--trust): env.id = " + kCartPolePort +
                                   ": an env that runs the Python code it names (interpreter: "
                                   "env.python " +
                                   kPython + ")";
  const std::string announced_python =
      "trusting " + origin + " (--trust): env.python = " + kPython + ": a program to run";
  const auto said = stderr_of("eval --model " + model + " --episodes 2 --trust");
  INFO(said.output);
  CHECK(said.exit_code == 0);
  CHECK(said.output.find(announced_id + "\n") != std::string::npos);
  CHECK(said.output.find(announced_python + "\n") != std::string::npos);
  const auto eval = run_rlrun_python("eval --model " + model + " --episodes 2 --trust");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("PPO on " + kCartPolePort +
                         ", 2 episodes (deterministic): mean_reward = ") != std::string::npos);

  const auto record = run_rlrun_python("record --model " + model + " --frames " + dir / "frames" +
                                       " --trust --episodes 1");
  INFO(record.output);
  CHECK(record.exit_code == 0);
  CHECK(record.output.find(announced_id) != std::string::npos);
  CHECK(fs::exists(dir / "frames/frame_000000.png"));

  // export builds no env (the model file records the env's spaces): nothing it names runs, so
  // it needs no one's word, and --trust has nothing to announce.
  for (const char* trust : {"", " --trust"}) {
    const auto exported =
        run_rlrun_python("export --model " + model + " --output " + dir / "policy.onnx" + trust);
    INFO(exported.output);
    CHECK(exported.exit_code == 0);
    CHECK(exported.output.find("trusting") == std::string::npos);
    CHECK(fs::file_size(dir / "policy.onnx") > 100);
  }
  // --set is still taken, silently.
  const auto vouched = run_rlrun_python("export --model " + model + " --output " +
                                        dir / "vouched.onnx --set env.id=" + kCartPolePort +
                                        " --set env.python=" + kPython);
  INFO(vouched.output);
  CHECK(vouched.exit_code == 0);
  CHECK(vouched.output.find("trusting") == std::string::npos);
  // A model of a built-in env exports with neither, also when its run wrote TensorBoard files
  // (the model's run.tensorboard_log is where training wrote: nothing that loads it writes
  // there, so it needs no one's word; it refused eval, record and export before).
  const auto cartpole = run_rlrun("train " + kSourceDir +
                                  "/configs/cartpole_ppo.yaml --timesteps 64 "
                                  "--out " +
                                  dir / "builtin --tensorboard-log " + dir / "tb");
  REQUIRE(cartpole.exit_code == 0);
  const auto plain = run_rlrun("export --model " + dir / "builtin/cartpole_ppo/seed1/model.zip" +
                               " --output " + dir / "cartpole.onnx");
  INFO(plain.output);
  CHECK(plain.exit_code == 0);
  CHECK(plain.output.find("trusting") == std::string::npos);
  const auto evaluated =
      run_rlrun("eval --model " + dir / "builtin/cartpole_ppo/seed1/model.zip" + " --episodes 1");
  INFO(evaluated.output);
  CHECK(evaluated.exit_code == 0);
}

// A traffic model trained on one's own scenario (a copy of the shipped one, outside rlrun's
// data directory) needed --set env.kwargs.scenario=... on every eval.
TEST_CASE("trust: --trust evaluates a traffic model of one's own scenario",
          "[cli][security][traffic]") {
  TempDir dir("trust_scenario");
  fs::copy(kSourceDir + "/sumo_data/single_intersection", dir / "single_intersection",
           fs::copy_options::recursive);
  write_file(dir / "mine.yaml", "name: mine\nsumocfg: single_intersection/single.sumocfg\n");
  const std::string sumo = "SUMO_HOME=/usr/share/sumo " + std::string(RLRUN_BINARY);
  const auto trained = run_command(
      sumo + " train " + kSourceDir + "/configs/traffic_dqn.yaml --timesteps 40 --out " +
      dir / "runs --set env.kwargs.scenario=" + dir / "mine.yaml" +
      " --set env.kwargs.num_seconds=100 --set algo.learning_starts=20");
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  const std::string model = dir / "runs/traffic_dqn/seed1/model.zip";
  const auto refused = run_command(sumo + " eval --model " + model + " --episodes 1");
  INFO(refused.output);
  CHECK(refused.exit_code == 2);
  CHECK(refused.output.find("--set env.kwargs.scenario=" + dir / "mine.yaml") != std::string::npos);
  CHECK(refused.output.find("Or pass --trust") != std::string::npos);
  const auto eval = run_command(sumo + " eval --model " + model + " --episodes 1 --trust");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("trusting " + model + ":config.yaml (--trust): env.kwargs.scenario = " +
                         dir / "mine.yaml: a simulator input file") != std::string::npos);
  CHECK(eval.output.find("DQN on TrafficSignal-v0, 1 episode (deterministic): mean_reward = ") !=
        std::string::npos);
}
