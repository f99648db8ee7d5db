// Camera observations of the gripper tasks (envs/gripper/gripper_camera_observation.hpp):
// obs_type state / pixels / both, the fixed and the wrist camera, image_size; the image is the
// scene the env is in (the cube where Bullet put it, the wrist view moving with the palm), the
// state part equals the state-only env's observation, the goal tasks keep vector goals for HER,
// and a CNN policy trains on them through the CLI.
#include <catch2/catch.hpp>
#include <fstream>
#include <string>
#include <vector>

#include "rlrun/envs/gripper/gripper_goal_env.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

GripperLift::Config lift_config(const std::string& obs_type, const std::string& camera,
                                int size = 64) {
  GripperLift::Config config;
  config.camera.obs_type = obs_type;
  config.camera.camera = camera;
  config.camera.image_size = size;
  return config;
}

// Pixels of the cube's red (200, 40, 40), shaded by the light: red well above green and blue.
int red_pixels(std::span<const float> image) {
  int n = 0;
  for (size_t i = 0; i + 2 < image.size(); i += 3)
    n += image[i] > 90 && image[i + 1] < 0.5f * image[i] && image[i + 2] < 0.5f * image[i];
  return n;
}

}  // namespace

TEST_CASE("gripper camera: spaces of obs_type state, pixels and both", "[gripper][camera]") {
  CHECK(GripperLift(lift_config("state", "fixed")).observation_space().describe() ==
        "Box(-inf, inf, (26,), float32)");
  CHECK(GripperLift(lift_config("pixels", "fixed", 84)).observation_space().describe() ==
        "Box(0, 255, (84, 84, 3), uint8)");
  CHECK(GripperLift(lift_config("both", "wrist", 48)).observation_space().describe() ==
        "Dict('pixels': Box(0, 255, (48, 48, 3), uint8), 'state': Box(-inf, inf, (26,), "
        "float32))");
  CHECK_THROWS_WITH(GripperLift(lift_config("rgb", "fixed")), Catch::Contains("obs_type"));
  CHECK_THROWS_WITH(GripperLift(lift_config("pixels", "top")), Catch::Contains("camera"));
  CHECK_THROWS_AS(GripperLift(lift_config("pixels", "fixed", 8)), std::invalid_argument);
}

TEST_CASE("gripper camera: the image shows the scene, the state part is the state",
          "[gripper][camera]") {
  GripperLift state_env(lift_config("state", "fixed")), both_env(lift_config("both", "fixed"));
  std::vector<float> s(state_env.observation_space().flat_dim());
  std::vector<float> b(both_env.observation_space().flat_dim());
  state_env.reset(4, s);
  both_env.reset(4, b);
  const Space& space = both_env.observation_space();
  const std::span<const float> image(b.data() + space.offset(0), 64 * 64 * 3);
  const std::span<const float> state(b.data() + space.offset(1), 26);
  CHECK(std::vector<float>(state.begin(), state.end()) == s);
  CHECK(red_pixels(image) > 10);  // the cube, from the front-right camera
  for (float v : image) REQUIRE((v >= 0 && v <= 255 && v == static_cast<float>(int(v))));
  // Moving the palm changes the picture (the fixed camera sees it move) and nothing else
  // differs from the state-only env.
  const std::vector<float> before(image.begin(), image.end());
  const float down[4] = {0.5f, 0, -1, -1};
  for (int t = 0; t < 3; ++t) {
    state_env.step(down, s);
    both_env.step(down, b);
  }
  CHECK(std::vector<float>(state.begin(), state.end()) == s);
  CHECK(std::vector<float>(image.begin(), image.end()) != before);
}

TEST_CASE("gripper camera: the wrist camera moves with the palm", "[gripper][camera]") {
  GripperLift env(lift_config("pixels", "wrist"));
  std::vector<float> obs(env.observation_space().flat_dim()), first;
  env.reset(2, obs);
  first = obs;
  const int red_at_start = red_pixels(obs);
  // Above the cube and lower (GripperLift-v0 starts the palm off the cube): the cube fills
  // more of the view as the camera comes down towards it.
  const float down[4] = {0, 0, -1, -1};
  for (int t = 0; t < 6; ++t) env.step(down, obs);
  CHECK(obs != first);
  const Vec3 g = env.world().grasp_point(), c = env.world().cube_position();
  INFO("grasp " << g[0] << " " << g[1] << " " << g[2] << ", cube " << c[0] << " " << c[1]);
  CHECK(red_pixels(obs) != red_at_start);
}

TEST_CASE("gripper camera: goal tasks keep vector goals beside the image",
          "[gripper_goal][camera]") {
  GripperGoalEnv::Config config;
  config.camera.obs_type = "pixels";
  config.camera.image_size = 40;
  GripperPush pixels(config);
  CHECK(pixels.observation_space().describe() ==
        "Dict('achieved_goal': Box(-inf, inf, (3,), float32), 'desired_goal': Box(-inf, inf, "
        "(3,), float32), 'observation': Box(0, 255, (40, 40, 3), uint8))");
  config.camera.obs_type = "both";
  GripperPush both(config);
  GripperPush state(GripperGoalEnv::Config{});
  CHECK(both.observation_space().keys() ==
        std::vector<std::string>{"achieved_goal", "desired_goal", "observation", "pixels"});
  std::vector<float> ob(both.observation_space().flat_dim()),
      os(state.observation_space().flat_dim());
  std::vector<float> op(pixels.observation_space().flat_dim());
  both.reset(3, ob);
  state.reset(3, os);
  pixels.reset(3, op);
  // achieved_goal, desired_goal and observation as in the state-only env; the goals also in the
  // pixels-only one.
  CHECK(std::vector<float>(ob.begin(), ob.begin() + os.size()) == os);
  CHECK(std::vector<float>(op.begin(), op.begin() + 6) ==
        std::vector<float>(os.begin(), os.begin() + 6));
  CHECK(red_pixels(std::span<const float>(op).subspan(6)) > 5);
}

TEST_CASE("gripper camera: SAC CnnPolicy and MultiInputPolicy train on it through the CLI",
          "[gripper][camera][cli]") {
  TempDir dir("gripper_camera_cli");
  const std::string config = dir / "lift_pixels.yaml";
  std::ofstream(config)
      << "run: {name: lift_pixels, seed: 1, total_timesteps: 300, out_dir: " << dir.str()
      << "/runs}\n"
      << R"(env: {id: GripperLiftEasy-v0, kwargs: {obs_type: both, camera: wrist, image_size: 36}}
algo:
  id: SAC
  learning_starts: 100
  batch_size: 32
  buffer_size: 1000
  policy: {features_extractor_class: CombinedExtractor, net_arch: [32, 32], cnn_output_dim: 32}
)";
  const auto r = run_rlrun("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto e =
      run_rlrun("eval --model " + dir / "runs/lift_pixels/seed1/model.zip" + " --episodes 1");
  INFO(e.output);
  CHECK(e.exit_code == 0);
}
