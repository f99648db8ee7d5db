// GripperLift-v0 / GripperLiftEasy-v0 on the real Bullet physics: determinism, the scripted
// controller's success (the task is solvable with the env's actions and forces), the grip
// holding a lifted cube, the staged reward, scenario files, and the CLI (eval/record --policy
// scripted). The learning bar is hidden ([.slow]): tests/envs/test_gripper_lift.cpp's last case.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/scripted_grasp_policy.hpp"
#include "rlrun/rng.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

// One episode under actions drawn from `action_seed`'s stream: every observation and reward.
std::vector<float> random_episode(GripperLift& env, uint64_t seed, uint64_t action_seed) {
  Rng actions(action_seed);
  std::vector<float> obs(GripperLift::kObsSize), trace;
  env.reset(seed, obs);
  trace.insert(trace.end(), obs.begin(), obs.end());
  StepResult r;
  do {
    float a[4];
    env.action_space().sample(actions, a);
    r = env.step(a, obs);
    trace.insert(trace.end(), obs.begin(), obs.end());
    trace.push_back(static_cast<float>(r.reward));
  } while (!r.truncated);
  return trace;
}

double scripted_success_rate(GripperLift& env, int episodes, uint64_t seed) {
  std::vector<float> obs(GripperLift::kObsSize);
  int successes = 0;
  for (int e = 0; e < episodes; ++e) {
    env.reset(e == 0 ? std::optional<uint64_t>(seed) : std::nullopt, obs);
    StepResult r;
    do r = env.step(scripted_grasp_action(env), obs);
    while (!r.truncated);
    successes += env.success();
  }
  return static_cast<double>(successes) / episodes;
}

}  // namespace

TEST_CASE("GripperLift: spaces, the same seed gives the same episode bit for bit", "[gripper]") {
  GripperLift env;
  CHECK(env.observation_space().describe() == "Box(-inf, inf, (26,), float32)");
  CHECK(env.action_space().describe() == "Box(-1.0, 1.0, (4,), float32)");
  const auto first = random_episode(env, 42, 7);
  GripperLift other;
  const auto second = random_episode(other, 42, 7);
  CHECK(first.size() == 51 * 26 + 50);         // reset + 50 steps (scenario episode_steps)
  CHECK(first == second);                      // a fresh env, the same floats
  CHECK(random_episode(env, 42, 7) == first);  // the same env after other episodes
  CHECK(random_episode(env, 43, 7) != first);
}

TEST_CASE("GripperLift: the scripted controller lifts the cube in every episode", "[gripper]") {
  GripperLift full;
  CHECK(scripted_success_rate(full, 30, 1) == 1.0);
  GripperLiftEasy easy;
  CHECK(scripted_success_rate(easy, 30, 1) == 1.0);
}

TEST_CASE("GripperLift: a held cube does not slip down, rest is rest", "[gripper]") {
  GripperLift env;
  std::vector<float> obs(GripperLift::kObsSize);
  env.reset(5, obs);
  // Untouched, the cube stays where it was put (no drift from the solver).
  const Vec3 start = env.world().cube_position();
  const float away[4] = {0, 0, 1, -1};
  for (int i = 0; i < 10; ++i) env.step(away, obs);
  const Vec3 rested = env.world().cube_position();
  CHECK(std::abs(rested[2] - start[2]) < 1e-4);
  CHECK(std::hypot(rested[0] - start[0], rested[1] - start[1]) < 1e-4);
  // Grasp and lift with the scripted controller, then hold still for 24 steps (1 s): the
  // study's failure mode was a held box creeping down ~19 mm/s.
  env.reset(5, obs);
  int steps = 0;
  while (!env.success() && steps < 40) {
    env.step(scripted_grasp_action(env), obs);
    ++steps;
  }
  REQUIRE(env.success());
  for (int i = 0; i < 4; ++i) env.step(scripted_grasp_action(env), obs);  // settle at the top
  const double held = env.world().cube_position()[2];
  const float hold[4] = {0, 0, 0, 1};
  for (int i = 0; i < 24; ++i) env.step(hold, obs);
  INFO("cube height " << held << " -> " << env.world().cube_position()[2]);
  CHECK(std::abs(env.world().cube_position()[2] - held) < 0.002);
  CHECK(env.success());
}

TEST_CASE("GripperLift: the staged reward and the observation", "[gripper]") {
  GripperLiftEasy env;
  std::vector<float> obs(GripperLift::kObsSize);
  env.reset(3, obs);
  const Vec3 cube = env.world().cube_position(), grasp = env.world().grasp_point();
  for (int k = 0; k < 3; ++k) {
    CHECK(obs[k] == Approx(grasp[k]));
    CHECK(obs[8 + k] == Approx(cube[k]));
    CHECK(obs[21 + k] == Approx(cube[k] - grasp[k]));
  }
  CHECK(obs[6] == Approx(GripperWorld::kMaxOpening).margin(1e-4));  // open at the start
  const float stay[4] = {0, 0, 0, -1};
  const StepResult r = env.step(stay, obs);
  const double d = std::sqrt(obs[21] * obs[21] + obs[22] * obs[22] + obs[23] * obs[23]);
  CHECK(r.reward == Approx(1 - std::tanh(10 * d)).margin(1e-5));  // reach only: not touching
  CHECK(obs[24] == 0.0f);
  CHECK(obs[25] == 0.0f);
  // Through a whole scripted episode: rewards never exceed 2.25, which success pays.
  env.reset(3, obs);
  StepResult s;
  double best = 0;
  do {
    s = env.step(scripted_grasp_action(env), obs);
    best = std::max(best, s.reward);
    CHECK(s.reward <= 2.25 + 1e-12);
    if (env.success()) CHECK(s.reward == 2.25);
    CHECK_FALSE(s.terminated);  // no early termination on success
  } while (!s.truncated);
  CHECK(best == 2.25);
  CHECK(env.info().get(env.info().find("is_success")) == 1.0);
}

TEST_CASE("GripperLift: scenario files", "[gripper]") {
  CHECK(load_grasp_scenario("scenarios/grasp/lift.yaml").episode_steps == 50);
  CHECK(load_grasp_scenario("scenarios/grasp/lift_easy.yaml").palm_above_cube);
  TempDir dir("grasp_scenario");
  std::ofstream(dir / "typo.yaml") << "name: x\ncube_sise: [0.05, 0.05]\n";
  CHECK_THROWS_WITH(
      load_grasp_scenario(dir / "typo.yaml"),
      Catch::Contains("typo.yaml:2:1") && Catch::Contains("did you mean 'cube_size'"));
  std::ofstream(dir / "range.yaml") << "cube_mass: [0.2, 0.1]\n";
  CHECK_THROWS_WITH(load_grasp_scenario(dir / "range.yaml"), Catch::Contains("low <= high"));
  std::ofstream(dir / "big.yaml") << "cube_size: [0.05, 0.09]\n";
  CHECK_THROWS_WITH(load_grasp_scenario(dir / "big.yaml"), Catch::Contains("up to 0.08 m"));
  std::ofstream(dir / "short.yaml") << "episode_steps: 20\ncube_x: [0, 0]\ncube_y: [0, 0]\n";
  GripperLift::Config config;
  config.scenario = dir / "short.yaml";
  GripperLift env(config);
  std::vector<float> obs(GripperLift::kObsSize);
  env.reset(1, obs);
  CHECK(env.world().cube_position()[0] == Approx(0).margin(1e-9));
  int steps = 0;
  const float a[4] = {0, 0, 0, 0};
  while (!env.step(a, obs).truncated) ++steps;
  CHECK(steps + 1 == 20);
  GripperLift::Config missing;
  missing.scenario = "no/such.yaml";
  CHECK_THROWS_WITH(GripperLift(missing), Catch::Contains("does not exist"));
}

TEST_CASE("eval and record --policy scripted on the grasp task", "[gripper][cli]") {
  TempDir dir("gripper_cli");
  const auto r = run_rlrun("eval --env GripperLift-v0 --policy scripted --episodes 10 --csv " +
                           dir / "scripted.csv");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("scripted on GripperLift-v0, 10 episodes") != std::string::npos);
  CHECK(r.output.find("success_rate = 1.000") != std::string::npos);
  const auto video =
      run_rlrun("record --env GripperLiftEasy-v0 --policy scripted --output " + dir / "lift.mp4");
  INFO(video.output);
  REQUIRE(video.exit_code == 0);
  CHECK(probe_video(dir / "lift.mp4").find("h264,480,480,51") !=
        std::string::npos);  // reset + 50 steps
  const auto wrong = run_rlrun("eval --env CartPole-v1 --policy scripted --episodes 1");
  CHECK(wrong.exit_code == 2);
  CHECK(wrong.output.find("policy 'scripted' does not come with CartPole-v1; its policies: "
                          "random") != std::string::npos);
  const auto neither = run_rlrun("eval --policy scripted --episodes 1");
  CHECK(neither.exit_code == 2);
}

// The bounded learning bar: configs/grasp_easy_sac.yaml as shipped (1e5 steps, about
// 7 minutes on two cores) reaches >= 0.9 success over 100 evaluation episodes. Hidden.
TEST_CASE("grasp_easy_sac reaches 0.9 success within 1e5 steps", "[.slow][gripper_learning]") {
  TempDir dir("gripper_learning");
  const auto train = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                               "/configs/grasp_easy_sac.yaml --out " + dir.str());
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const auto r = run_rlrun("eval --model " + dir / "grasp_easy_sac/seed1/model.zip" +
                           " --episodes 100 --seed 1000");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto at = r.output.find("success_rate = ");
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(r.output.substr(at + 15)) >= 0.9);
}
