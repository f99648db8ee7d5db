// Python envs inside rlrun (src/rlrun/envs/python/), through the real binary and the real
// interpreter (Debian's python3 + numpy), on the envs of tests/python_envs/rlrun_test_envs:
// a CartPole port, a continuous task, a Dict-observation task and envs that go wrong.
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <vector>

#include "envs/python_env_runner.hpp"
#include "runtime/video_probe.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

namespace {

const std::string kCartPolePort = "python:rlrun_test_envs.cartpole:CartPolePort";
const std::string kReach = "python:rlrun_test_envs.continuous:Reach1D";
const std::string kDictGoal = "python:rlrun_test_envs.continuous:DictGoal";
const std::string kBrightSide = "python:rlrun_test_envs.pixels:BrightSide";
const std::string kPpoZoo =
    "id: PPO, n_steps: 32, batch_size: 256, n_epochs: 20, gamma: 0.98, gae_lambda: 0.8, "
    "learning_rate: lin_0.001, clip_range: lin_0.2, ent_coef: 0.0";

// The r and l columns of a monitor file (its header names the env, so it is skipped).
std::vector<std::string> episodes(const std::string& monitor_csv) {
  std::stringstream in(read_text(monitor_csv));
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);  // #{"t_start": ..., "env_id": ...}
  std::getline(in, line);  // r,l,t,...
  while (std::getline(in, line)) {
    const auto first = line.find(',');
    const auto second = line.find(',', first + 1);
    rows.push_back(line.substr(0, second));
  }
  return rows;
}

double mean_reward(const std::string& output) {
  const auto at = output.find("mean_reward = ");
  return at == std::string::npos ? -1e9 : std::stod(output.substr(at + 14));
}

}  // namespace

TEST_CASE("check-env passes the Python test envs, with python3 from PATH", "[python]") {
  for (const std::string& id : {kCartPolePort, kReach, kDictGoal}) {
    // The default interpreter is `python3` on PATH: put Debian's first.
    const auto r =
        run_command("cd " + kSourceDir + " && PATH=/usr/bin:$PATH PYTHONPATH=" + kSourceDir +
                    "/tests/python_envs " + RLRUN_BINARY + " check-env " + id);
    INFO(r.output);
    CHECK(r.exit_code == 0);
  }
}

TEST_CASE("Python envs train deterministically: same seed, same episodes", "[python]") {
  // Four workers stepping in parallel, twice with seed 1: every env's episodes are the same
  // (env i is seeded 1 + i; the workers' timing does not matter). Seed 2 differs.
  TempDir dir("python_same_run");
  std::vector<std::vector<std::string>> runs;
  for (const char* name : {"a", "b", "c"}) {
    const std::string seed = name[0] == 'c' ? "2" : "1";
    const auto r = run_rlrun_python("train " +
                                    python_experiment(dir.str(), name, kCartPolePort, kPpoZoo, 4096,
                                                      4, ", max_episode_steps: 500") +
                                    " --seed " + seed);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    std::vector<std::string> all;
    for (int i = 0; i < 4; ++i) {
      const auto e = episodes(dir / ("runs/" + std::string(name) + "/seed" + seed + "/" +
                                     std::to_string(i) + ".monitor.csv"));
      CHECK(e.size() > 10);
      all.insert(all.end(), e.begin(), e.end());
    }
    runs.push_back(all);
  }
  CHECK(runs[0] == runs[1]);
  CHECK(runs[0] != runs[2]);
}

TEST_CASE("PPO learns the Python CartPole port to >= 475 with the zoo's settings",
          "[python][python_learning]") {
  TempDir dir("python_ppo");
  const std::string config = python_experiment(dir.str(), "cartpole_port", kCartPolePort, kPpoZoo,
                                               100000, 8, ", max_episode_steps: 500");
  const auto train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  // A model file is untrusted: its Python env id runs code, so rlrun asks for it on the
  // command line before building the env.
  const std::string model = dir / "runs/cartpole_port/seed1/model.zip";
  const auto refused = run_rlrun_python("eval --model " + model + " --episodes 2");
  INFO(refused.output);
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("--set env.id=" + kCartPolePort) != std::string::npos);
  const auto eval = run_rlrun_python("eval --model " + model +
                                     " --episodes 10 --seed 1000 --set env.id=" + kCartPolePort +
                                     " --set env.python=" + kPython);
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(mean_reward(eval.output) >= 475);
}

TEST_CASE("SAC learns a continuous Python task", "[python][python_learning]") {
  TempDir dir("python_sac");
  const std::string config = python_experiment(
      dir.str(), "reach", kReach,
      "id: SAC, learning_starts: 200, batch_size: 64, policy: {net_arch: [64, 64]}", 4000);
  const auto train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / "runs/reach/seed1/model.zip";
  const auto eval =
      run_rlrun_python("eval --model " + model + " --episodes 20 --seed 7 --set env.id=" + kReach +
                       " --set env.python=" + kPython);
  const auto random =
      run_rlrun_python("eval --env " + kReach +
                       " --policy random --episodes 20 --seed 7 --set env.python=" + kPython);
  INFO(eval.output << random.output);
  REQUIRE(eval.exit_code == 0);
  REQUIRE(random.exit_code == 0);
  // A random policy: about -14; a policy that walks to the target: about -3.
  CHECK(mean_reward(eval.output) > -6.0);
  CHECK(mean_reward(random.output) < -9.0);
}

TEST_CASE("A Dict-observation Python env trains and its is_success reaches monitor.csv",
          "[python]") {
  TempDir dir("python_dict");
  const std::string config =
      python_experiment(dir.str(), "dict_goal", kDictGoal, "id: PPO, n_steps: 64", 1024, 2);
  const auto r = run_rlrun_python("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string monitor = read_text(dir / "runs/dict_goal/seed1/0.monitor.csv");
  CHECK(monitor.find("r,l,t,is_success") != std::string::npos);
  CHECK(monitor.find(",True") != std::string::npos);
  const std::string resolved = read_text(dir / "runs/dict_goal/seed1/config.yaml");
  CHECK(resolved.find("python: " + kPython) != std::string::npos);
}

TEST_CASE("A Python env's uint8 Box is an image: CnnPolicy takes it, the replay buffer keeps bytes",
          "[python][image]") {
  TempDir dir("python_pixels");
  // SB3's CnnPolicy for DQN on Box(0, 255, (36, 36, 1), uint8), buffer in bytes, stored once.
  const std::string config = python_experiment(
      dir.str(), "bright", kBrightSide,
      "id: DQN, buffer_size: 400, learning_starts: 100, train_freq: 4, batch_size: 16, "
      "optimize_memory_usage: true, handle_timeout_termination: false, "
      "policy: {features_extractor_class: NatureCNN, features_dim: 16, net_arch: []}",
      400, 1, "", "checkpoint: {freq: 200}\n");
  const auto r = run_rlrun_python("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string resolved = read_text(dir / "runs/bright/seed1/config.yaml");
  CHECK(resolved.find("optimize_memory_usage: true") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "runs/bright/seed1/checkpoints/step_200.zip"));
  const auto check =
      run_command("cd " + kSourceDir + " && PATH=/usr/bin:$PATH PYTHONPATH=" + kSourceDir +
                  "/tests/python_envs " + RLRUN_BINARY + " check-env " + kBrightSide);
  INFO(check.output);
  CHECK(check.exit_code == 0);
  CHECK(check.output.find("Box(0, 255, (36, 36, 1), uint8)") != std::string::npos);
  // The same pictures as float32: SB3's NatureCNN assertion, saying what an image is.
  const std::string floats =
      python_experiment(dir.str(), "floats", "python:rlrun_test_envs.pixels:FloatBrightSide",
                        "id: DQN, policy: {features_extractor_class: NatureCNN}", 400);
  const auto refused = run_rlrun_python("train " + floats);
  INFO(refused.output);
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("you should use NatureCNN only with images, not with Box(0.0, 255.0, "
                            "(36, 36, 1), float32)") != std::string::npos);
  CHECK(refused.output.find("dtype uint8") != std::string::npos);
}

TEST_CASE("rlrun record films a Python env through its render()", "[python]") {
  TempDir dir("python_record");
  const std::string video = dir / "port.mp4";
  const auto r = run_rlrun_python(
      "record --env " + kCartPolePort +
      " --policy random --episodes 1 --seed 3 --set env.python=" + kPython + " --output " + video);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string probe = probe_video(video);
  INFO(probe);
  // The env's own 300x200 frames, one per step plus the first.
  CHECK(probe.find("h264,300,200,") != std::string::npos);
}

TEST_CASE("the documented Python env example trains and evaluates as docs/python.md says",
          "[python]") {
  TempDir dir("python_example");
  const std::string example = kSourceDir + "/examples/python_env";
  // As the docs run it: from the example's directory, python3 from PATH (Debian's first).
  const auto train = run_command(
      "cd " + example + " && PATH=/usr/bin:$PATH " + RLRUN_BINARY +
      " train walk_to_target_ppo.yaml --timesteps 2048 --set eval.freq=0 --out " + dir.str());
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const auto eval = run_command("cd " + example + " && PATH=/usr/bin:$PATH " + RLRUN_BINARY +
                                " eval --model " + dir.str() +
                                "/walk_to_target_ppo/seed1/model.zip --episodes 5 --set "
                                "env.id=python:walk_to_target:WalkToTarget");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("success_rate = ") != std::string::npos);
  CHECK(read_text(dir / "walk_to_target_ppo/seed1/0.monitor.csv").find("r,l,t,is_success") !=
        std::string::npos);
}

TEST_CASE("env.python: a virtualenv's interpreter runs the env", "[python]") {
  TempDir dir("python_venv");
  // A virtualenv of Debian's python3 that sees its numpy (--system-site-packages), as a user
  // with their own environment has; rlrun is told to use it, not python3 on PATH.
  const auto venv = run_command("/usr/bin/python3 -m venv --without-pip --system-site-packages " +
                                dir.str() + "/venv");
  INFO(venv.output);
  REQUIRE(venv.exit_code == 0);
  const auto r = run_rlrun_python(
      "check-env python:rlrun_test_envs.continuous:Reach1D --episodes 2 --python " + dir.str() +
      "/venv/bin/python");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  const auto wrong =
      run_rlrun_python("check-env python:rlrun_test_envs.continuous:Reach1D --python " + dir.str() +
                       "/venv/bin/no-python");
  CHECK(wrong.exit_code != 0);
  CHECK(wrong.output.find("cannot run the Python interpreter") != std::string::npos);
}

TEST_CASE("rlrun's wrappers stack on a Python env, deterministically", "[python]") {
  // NormalizeObservation (statistics shared by the 4 copies) splits steps like TimeLimit and
  // Monitor (env/split_step.hpp); FrameStack does not, so its workers step one at a time.
  // Either way: the same seed gives the same episodes.
  TempDir dir("python_wrappers");
  for (const std::string wrapper : {"NormalizeObservation", "FrameStack, n_stack: 2"}) {
    std::string monitors[2];
    for (int run = 0; run < 2; ++run) {
      const std::string name = "wrapped" + std::to_string(run) + wrapper.substr(0, 5);
      const auto r = run_rlrun_python(
          "train " +
          python_experiment(dir.str(), name, kCartPolePort, "id: PPO, n_steps: 64", 2048, 4,
                            ", max_episode_steps: 500, wrappers: [{id: " + wrapper + "}]"));
      INFO(r.output);
      REQUIRE(r.exit_code == 0);
      for (int i = 0; i < 4; ++i)
        for (const auto& e :
             episodes(dir / ("runs/" + name + "/seed1/" + std::to_string(i) + ".monitor.csv")))
          monitors[run] += e + "\n";
    }
    INFO(wrapper);
    CHECK(monitors[0].size() > 100);
    CHECK(monitors[0] == monitors[1]);
  }
}
