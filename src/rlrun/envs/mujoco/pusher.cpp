#include "rlrun/envs/mujoco/pusher.hpp"

#include "rlrun/envs/mujoco/model_shape.hpp"
#include "rlrun/envs/mujoco/numpy_math.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kFrameSkip = 5;
constexpr ModelShape kShape{.nq = 11, .nv = 11, .nu = 7};
constexpr size_t kArmJoints = 7;

std::string model_file(const Pusher::Config& config) {
  return model_path(config.xml_file.value, "pusher.xml");
}

}  // namespace

Pusher::Pusher(const Config& config)
    : MujocoEnv("Pusher-v4", model_file(config), kFrameSkip, 23),
      tips_arm_(body_id("tips_arm")),
      object_(body_id("object")),
      goal_(body_id("goal")) {
  require_shape(model(), kShape, id(), model_file(config));
  set_default_camera({.trackbodyid = -1, .distance = 4.0});
  Info& info = mutable_info();
  key_reward_dist_ = info.add_key("reward_dist");
  key_reward_ctrl_ = info.add_key("reward_ctrl");
}

// Gymnasium's reset_model writes the cylinder and goal positions into init_qpos itself (qpos
// is init_qpos, not a copy). The next reset overwrites the same four entries and the arm's
// seven are never written, so only init_qpos shows it; rlrun's init_qpos stays the model's
// rest pose (docs/mujoco.md).
void Pusher::reset_model(Rng& rng) {
  std::vector<double> qpos(init_qpos().begin(), init_qpos().end());
  const std::array<double, 2> goal{0.0, 0.0};
  std::array<double, 2> cylinder{};
  do {
    cylinder = {rng.uniform(-0.3, 0.0), rng.uniform(-0.2, 0.2)};
  } while (!(euclidean_norm(std::array{cylinder[0] - goal[0], cylinder[1] - goal[1]}) > 0.17));
  qpos[7] = cylinder[0];
  qpos[8] = cylinder[1];
  qpos[9] = goal[0];
  qpos[10] = goal[1];
  std::vector<double> qvel = uniform_around(init_qvel(), -0.005, 0.005, rng);
  for (size_t i = kArmJoints; i < qvel.size(); ++i) qvel[i] = 0.0;
  set_state(qpos, qvel);
}

std::array<double, 3> Pusher::between(int a, int b) const {
  const double* from = body_xpos(a);
  const double* to = body_xpos(b);
  return {from[0] - to[0], from[1] - to[1], from[2] - to[2]};
}

void Pusher::observe(std::span<float> obs) const {
  ObservationWriter(obs)
      .put(qpos().first(kArmJoints))
      .put(qvel().first(kArmJoints))
      .put({body_xpos(tips_arm_), 3})
      .put({body_xpos(object_), 3})
      .put({body_xpos(goal_), 3});
}

StepResult Pusher::step(std::span<const float> action, std::span<float> obs) {
  // Gymnasium measures before simulating: the distances of the state the action is taken in.
  const double reward_near = -euclidean_norm(between(object_, tips_arm_));
  const double reward_dist = -euclidean_norm(between(object_, goal_));
  const double reward_ctrl = -sum_of_squares(action);  // a float32 in Gymnasium, widened here
  const double reward = reward_dist + 0.1 * reward_ctrl + 0.5 * reward_near;
  if (!do_simulation(action)) return end_unstable(obs);
  observe(obs);
  Info& info = mutable_info();
  info.set(key_reward_dist_, reward_dist);
  info.set(key_reward_ctrl_, reward_ctrl);
  return {reward, false, false};
}

}  // namespace rlrun::mujoco
