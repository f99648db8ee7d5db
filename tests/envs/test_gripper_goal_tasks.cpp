// GripperReach-v0, GripperPush-v0, GripperPickAndPlace-v0 (envs/gripper/gripper_goal_env.hpp):
// panda-gym's goal tasks on the Bullet gripper. Spaces, the GoalEnv reward against step(),
// success, determinism, the scenario's goal ranges, the scripted baselines' success, the env
// checker, the goal marker in the picture, scenario file errors and the CLI.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/envs/gripper/goal_scenario.hpp"
#include "rlrun/envs/gripper/gripper_goal_env.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/scripted_goal_policy.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/rng.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

constexpr GoalTask kTasks[] = {GoalTask::kReach, GoalTask::kPush, GoalTask::kPickAndPlace};

std::unique_ptr<GripperGoalEnv> make(GoalTask task, GripperGoalEnv::Config config = {}) {
  return std::make_unique<GripperGoalEnv>(task, config);
}

// Flat layout: keys sorted (achieved_goal, desired_goal, observation).
constexpr int kAchieved = 0, kDesired = 3, kObservation = 6;

struct Step {
  std::vector<float> obs;
  StepResult result;
  double is_success;
};

// One episode (to termination or truncation): random actions from `action_seed`, or the
// scripted controller when action_seed is 0.
std::vector<Step> episode(GripperGoalEnv& env, std::optional<uint64_t> seed, uint64_t action_seed) {
  Rng actions(action_seed);
  const int n = env.observation_space().flat_dim();
  std::vector<Step> steps;
  std::vector<float> obs(n);
  env.reset(seed, obs);
  steps.push_back({obs, {}, env.info().get(env.info().find("is_success"))});
  StepResult r;
  do {
    float a[4];
    if (action_seed) {
      env.action_space().sample(
          actions, std::span<float>(a, static_cast<size_t>(env.action_space().flat_dim())));
    } else {
      const auto s = scripted_goal_action(env);
      std::copy(s.begin(), s.end(), a);
    }
    r = env.step(std::span<const float>(a, env.action_space().flat_dim()), obs);
    steps.push_back({obs, r, env.info().get(env.info().find("is_success"))});
  } while (!r.terminated && !r.truncated);
  return steps;
}

double scripted_success_rate(GripperGoalEnv& env, int episodes, uint64_t seed) {
  int successes = 0;
  for (int e = 0; e < episodes; ++e) {
    const auto steps = episode(env, e == 0 ? std::optional<uint64_t>(seed) : std::nullopt, 0);
    successes += steps.back().is_success == 1.0;
  }
  return static_cast<double>(successes) / episodes;
}

}  // namespace

TEST_CASE("Goal tasks: spaces, Dict keys, GoalEnv, observation layout", "[gripper_goal]") {
  const int sizes[] = {6, 18, 19}, actions[] = {3, 3, 4};
  for (int t = 0; t < 3; ++t) {
    auto env = make(kTasks[t]);
    INFO(env->id());
    const Space& space = env->observation_space();
    REQUIRE(space.is_dict());
    CHECK(space.keys() == std::vector<std::string>{"achieved_goal", "desired_goal", "observation"});
    CHECK(space.subspaces()[0].describe() == "Box(-inf, inf, (3,), float32)");
    CHECK(space.subspaces()[1].describe() == "Box(-inf, inf, (3,), float32)");
    CHECK(space.subspaces()[2].flat_dim() == sizes[t]);
    CHECK(env->action_space().describe() ==
          "Box(-1.0, 1.0, (" + std::to_string(actions[t]) + ",), float32)");
    CHECK(goal_env_of(*env) == env.get());
    std::vector<float> obs(space.flat_dim());
    env->reset(3, obs);
    const GripperWorld& w = env->world();
    const Vec3 grasp = w.grasp_point();
    for (int k = 0; k < 3; ++k) {
      CHECK(obs[kObservation + k] == static_cast<float>(grasp[k]));
      CHECK(obs[kDesired + k] == static_cast<float>(env->goal()[k]));
      CHECK(obs[kAchieved + k] == static_cast<float>(env->achieved_goal()[k]));
    }
    CHECK(w.has_cube() == (kTasks[t] != GoalTask::kReach));
    if (kTasks[t] == GoalTask::kReach) {
      for (int k = 0; k < 3; ++k) CHECK(obs[kAchieved + k] == obs[kObservation + k]);
    } else {
      const int cube_at = kObservation + (kTasks[t] == GoalTask::kPush ? 6 : 7);
      const Vec3 cube = w.cube_position();
      for (int k = 0; k < 3; ++k) {
        CHECK(obs[cube_at + k] == static_cast<float>(cube[k]));
        CHECK(obs[kAchieved + k] == static_cast<float>(cube[k]));
        CHECK(obs[cube_at + 3 + k] == 0.0f);  // unturned: roll, pitch, yaw 0
      }
    }
    if (kTasks[t] == GoalTask::kPickAndPlace)
      CHECK(obs[kObservation + 6] == Approx(0.0).margin(1e-4));  // fingers start closed
  }
}

TEST_CASE(
    "Goal tasks: compute_reward for a batch equals step()'s reward and success is d < threshold",
    "[gripper_goal]") {
  for (const char* reward_type : {"sparse", "dense"}) {
    for (GoalTask task : kTasks) {
      GripperGoalEnv::Config config;
      config.reward_type = reward_type;
      config.distance_threshold = task == GoalTask::kReach ? 0.05 : 0.07;
      config.terminate_on_success = false;  // whole episodes: both outcomes occur
      auto env = make(task, config);
      INFO(env->id() << " " << reward_type);
      std::vector<Step> steps;
      for (uint64_t a : {0, 11}) {  // scripted (reaches the goal) and random
        const auto e = episode(*env, 5, a);
        steps.insert(steps.end(), e.begin() + 1, e.end());
      }
      const Eigen::Index n = static_cast<Eigen::Index>(steps.size());
      Eigen::MatrixXf achieved(3, n), desired(3, n);
      for (Eigen::Index j = 0; j < n; ++j)
        for (int k = 0; k < 3; ++k) {
          achieved(k, j) = steps[j].obs[kAchieved + k];
          desired(k, j) = steps[j].obs[kDesired + k];
        }
      Eigen::RowVectorXf rewards(n);
      goal_env_of(*env)->compute_reward(achieved, desired, rewards);
      int successes = 0;
      for (Eigen::Index j = 0; j < n; ++j) {
        const float d = (achieved.col(j) - desired.col(j)).norm();
        CHECK(rewards[j] == static_cast<float>(steps[j].result.reward));
        const bool success = d < static_cast<float>(config.distance_threshold);
        CHECK(steps[j].is_success == (success ? 1.0 : 0.0));
        if (config.reward_type == "sparse")
          CHECK(steps[j].result.reward == (success ? 0.0 : -1.0));
        else
          CHECK(steps[j].result.reward == Approx(-d).epsilon(1e-6));
        CHECK_FALSE(steps[j].result.terminated);
        successes += success;
      }
      CHECK(successes > 0);
      CHECK(successes < n);
      // Relabelled goals: the reward of other pairs (HER's use).
      Eigen::MatrixXf same = achieved;
      goal_env_of(*env)->compute_reward(achieved, same, rewards);
      CHECK((rewards.array() == 0.0f).all());
    }
  }
}

TEST_CASE("Goal tasks: terminated on success (panda-gym), truncated after 50 steps",
          "[gripper_goal]") {
  for (GoalTask task : kTasks) {
    auto env = make(task);
    INFO(env->id());
    const auto scripted = episode(*env, 2, 0);
    CHECK(scripted.back().result.terminated);
    CHECK(scripted.back().is_success == 1.0);
    CHECK(scripted.back().result.reward == 0.0);
    for (size_t i = 1; i + 1 < scripted.size(); ++i) CHECK(scripted[i].result.reward == -1.0);
    // Random actions almost never succeed: the episode runs to the time limit.
    const auto random = episode(*env, 2, 9);
    if (!random.back().result.terminated) {
      CHECK(random.size() == 51);
      CHECK(random.back().result.truncated);
    }
  }
}

TEST_CASE("Goal tasks: the same seed gives the same episode bit for bit", "[gripper_goal]") {
  for (GoalTask task : kTasks) {
    auto a = make(task), b = make(task);
    INFO(a->id());
    const auto first = episode(*a, 42, 7), second = episode(*b, 42, 7);
    REQUIRE(first.size() == second.size());
    for (size_t i = 0; i < first.size(); ++i) {
      CHECK(first[i].obs == second[i].obs);
      CHECK(first[i].result.reward == second[i].result.reward);
    }
    const auto again = episode(*a, 42, 7);  // the same env after an episode
    CHECK(again.back().obs == first.back().obs);
    CHECK(episode(*a, 43, 7).front().obs != first.front().obs);
  }
}

TEST_CASE(
    "Goal tasks: goals and cubes within the scenario's ranges and half of PickAndPlace's "
    "goals in the air",
    "[gripper_goal]") {
  constexpr int kResets = 400;
  for (GoalTask task : kTasks) {
    auto env = make(task);
    INFO(env->id());
    const GoalTaskScenario& s = env->scenario();
    std::vector<float> obs(env->observation_space().flat_dim());
    int in_air = 0;
    double low_x = 1, high_x = -1;
    for (int i = 0; i < kResets; ++i) {
      env->reset(i == 0 ? std::optional<uint64_t>(17) : std::nullopt, obs);
      const Vec3 g = env->goal();
      CHECK(g[0] >= s.goal_x[0]);
      CHECK(g[0] <= s.goal_x[1]);
      CHECK(g[1] >= s.goal_y[0]);
      CHECK(g[1] <= s.goal_y[1]);
      low_x = std::min(low_x, g[0]);
      high_x = std::max(high_x, g[0]);
      const double height = g[2] - env->resting_height();
      CHECK(height >= s.goal_z[0]);
      CHECK(height <= s.goal_z[1]);
      in_air += height > 1e-9;
      CHECK((env->info().get(env->info().find("is_success")) == 0.0 || task == GoalTask::kReach));
      if (task != GoalTask::kReach) {
        const Vec3 c = env->world().cube_position();
        CHECK(c[0] >= s.cube.x[0]);
        CHECK(c[0] <= s.cube.x[1]);
        CHECK(c[1] >= s.cube.y[0]);
        CHECK(c[1] <= s.cube.y[1]);
        CHECK(c[2] == Approx(0.02));
        // goal_apart: never solved at the start.
        CHECK(GripperGoalEnv::distance(&obs[kAchieved], &obs[kDesired]) >= 0.05f);
      }
    }
    CHECK(low_x < s.goal_x[0] + 0.01);  // the whole range is used
    CHECK(high_x > s.goal_x[1] - 0.01);
    const double fraction = static_cast<double>(in_air) / kResets;
    if (task == GoalTask::kReach) CHECK(fraction == 1.0);
    if (task == GoalTask::kPush) CHECK(fraction == 0.0);
    if (task == GoalTask::kPickAndPlace) {
      CHECK(fraction > 0.42);  // 0.5 +- 3.2 standard deviations of 400 coin flips
      CHECK(fraction < 0.58);
    }
  }
  // The scenario defaults are panda-gym's: a 0.3 square, Reach up to 0.3 above the table.
  auto reach = make(GoalTask::kReach);
  CHECK(reach->scenario().goal_z == std::vector<double>{0.0, 0.3});
  CHECK(reach->scenario().goal_x == std::vector<double>{-0.15, 0.15});
}

TEST_CASE("Goal tasks: a world without the cube and GripperLift's world unchanged",
          "[gripper_goal]") {
  GripperWorld::Layout layout;
  layout.with_cube = false;
  GripperWorld empty(layout);
  CHECK_FALSE(empty.has_cube());
  CHECK_THROWS_AS(empty.cube_position(), std::logic_error);
  CHECK(empty.finger_contacts() == std::array<bool, 2>{false, false});
  // The palm and fingers move exactly as in a world with a cube far away from them.
  GripperWorld::Layout with = layout;
  with.with_cube = true;
  with.cube_position = {0.2, 0.2, 0.025};
  GripperWorld full(with);
  for (GripperWorld* w : {&empty, &full}) {
    w->command({0.05, -0.03, 0.1}, 0.02);
    w->step(30);
  }
  CHECK(empty.grasp_point() == full.grasp_point());
  CHECK(empty.opening() == full.opening());
  // A default Layout still has its cube (GripperLift's worlds: tests/envs/test_gripper_lift.cpp).
  GripperWorld lift{GripperWorld::Layout{}};
  CHECK(lift.has_cube());
  CHECK(lift.cube_position()[2] == Approx(0.025));
}

TEST_CASE("Goal tasks: the scripted controllers succeed", "[gripper_goal]") {
  // Measured: 1.000 for each task over 500 episodes (`rlrun eval --policy scripted --episodes
  // 500 --seed 1000`); here 100 episodes each (about 0.5 s), with margin.
  GripperReach reach;
  CHECK(scripted_success_rate(reach, 100, 1) == 1.0);
  GripperPush push;
  CHECK(scripted_success_rate(push, 100, 1) >= 0.95);
  GripperPickAndPlace pick;
  CHECK(scripted_success_rate(pick, 100, 1) >= 0.95);
}

TEST_CASE("Goal tasks: the env checker passes", "[gripper_goal]") {
  for (GoalTask task : kTasks) {
    auto env = make(task);
    INFO(env->id());
    const auto problems = check_env(*env, 3, 120);
    for (const auto& p : problems) INFO(p);
    CHECK(problems.empty());
  }
}

TEST_CASE("Goal tasks: the goal marker is drawn", "[gripper_goal]") {
  const auto green_pixels = [](const Frame& frame) {
    int n = 0;
    for (int y = 0; y < frame.height(); ++y)
      for (int x = 0; x < frame.width(); ++x) {
        const Rgb p = frame.pixel(x, y);
        n += p.g > 120 && p.g > 1.5 * p.r && p.g > 1.5 * p.b;
      }
    return n;
  };
  for (GoalTask task : kTasks) {
    auto env = make(task);
    INFO(env->id());
    std::vector<float> obs(env->observation_space().flat_dim());
    env->reset(4, obs);
    const RenderSpec spec = env->render_spec();
    Frame frame(spec.width, spec.height);
    REQUIRE(env->render(frame));
    CHECK(green_pixels(frame) > 30);
  }
  // GripperLift's picture has no green until the cube is lifted.
  GripperLift lift;
  std::vector<float> obs(GripperLift::kObsSize);
  lift.reset(4, obs);
  Frame frame(480, 480);
  lift.render(frame);
  CHECK(green_pixels(frame) == 0);
}

TEST_CASE("Goal tasks: scenario files and settings", "[gripper_goal]") {
  CHECK(load_goal_task_scenario("scenarios/grasp/push.yaml").goal_apart);
  CHECK(load_goal_task_scenario("scenarios/grasp/pick_and_place.yaml").goal_in_air_probability ==
        0.5);
  TempDir dir("goal_scenario");
  std::ofstream(dir / "typo.yaml") << "name: x\ngoal_in_air_probabilty: 0.3\n";
  CHECK_THROWS_WITH(load_goal_task_scenario(dir / "typo.yaml"),
                    Catch::Contains("typo.yaml:2:1") &&
                        Catch::Contains("did you mean 'goal_in_air_probability'"));
  std::ofstream(dir / "range.yaml") << "goal_x: [0.1, -0.1]\n";
  CHECK_THROWS_WITH(load_goal_task_scenario(dir / "range.yaml"),
                    Catch::Contains("range.yaml:1:") && Catch::Contains("low <= high"));
  std::ofstream(dir / "outside.yaml") << "goal_z: [0.0, 0.5]\n";
  CHECK_THROWS_WITH(load_goal_task_scenario(dir / "outside.yaml"), Catch::Contains("must lie in"));
  std::ofstream(dir / "p.yaml") << "goal_in_air_probability: 1.5\n";
  CHECK_THROWS_WITH(load_goal_task_scenario(dir / "p.yaml"), Catch::Contains("in [0, 1]"));
  // A scenario whose goals always sit on the cube cannot keep them apart.
  std::ofstream(dir / "stuck.yaml") << "cube_x: [0, 0]\ncube_y: [0, 0]\ngoal_x: [0, 0]\n"
                                       "goal_y: [0, 0]\ngoal_apart: true\n";
  GripperGoalEnv::Config config;
  config.scenario = dir / "stuck.yaml";
  GripperPush stuck(config);
  std::vector<float> obs(stuck.observation_space().flat_dim());
  CHECK_THROWS_WITH(stuck.reset(1, obs), Catch::Contains("no goal farther"));
  config.scenario = "";
  config.reward_type = "shaped";
  CHECK_THROWS_AS(GripperReach(config), std::invalid_argument);
  GripperGoalEnv::Config missing;
  missing.scenario = "no/such.yaml";
  CHECK_THROWS_WITH(GripperReach(missing), Catch::Contains("does not exist"));
}

TEST_CASE("eval and record --policy scripted on the goal tasks", "[gripper_goal][cli]") {
  TempDir dir("gripper_goal_cli");
  const auto r = run_rlrun("eval --env GripperPush-v0 --policy scripted --episodes 5");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("scripted on GripperPush-v0, 5 episodes") != std::string::npos);
  CHECK(r.output.find("success_rate = ") != std::string::npos);
  const auto video = run_rlrun("record --env GripperPickAndPlace-v0 --policy scripted --output " +
                               dir / "pick.mp4");
  INFO(video.output);
  REQUIRE(video.exit_code == 0);
  CHECK(probe_video(dir / "pick.mp4").find("h264,480,480,") != std::string::npos);
  const auto kwargs = run_rlrun(
      "eval --env GripperReach-v0 --policy scripted --episodes 3 --set "
      "env.kwargs.reward_type=dense");
  INFO(kwargs.output);
  CHECK(kwargs.exit_code == 0);
}
