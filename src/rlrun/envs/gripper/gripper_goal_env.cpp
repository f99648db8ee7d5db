#include "rlrun/envs/gripper/gripper_goal_env.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/gripper/goal_workspace.hpp"
#include "rlrun/envs/gripper/grasp_scenario.hpp"

namespace rlrun {

namespace {

constexpr int kMaxGoalDraws = 1000;  // goal_apart: redraws before the scenario is refused

double draw(Rng& rng, const std::vector<double>& range) { return rng.uniform(range[0], range[1]); }

const char* scenario_name(GoalTask task) {
  switch (task) {
    case GoalTask::kReach: return "reach";
    case GoalTask::kPush: return "push";
    case GoalTask::kPickAndPlace: return "pick_and_place";
  }
  return "";
}

// panda-gym's observation sizes: robot (ee position, velocity, + fingers width unless
// blocked) and task (object position, Euler angles, velocity, angular velocity).
int observation_size_of(GoalTask task) {
  switch (task) {
    case GoalTask::kReach: return 6;
    case GoalTask::kPush: return 6 + 12;
    case GoalTask::kPickAndPlace: return 7 + 12;
  }
  return 0;
}

// Roll, pitch, yaw (x, y, z) of a quaternion x, y, z, w: the Z-Y-X Tait-Bryan angles, the
// convention of PyBullet's getEulerFromQuaternion that panda-gym observes. At gimbal lock
// (pitch +-pi/2, a cube tipped onto a side) only yaw -+ roll is defined: roll is 0 and yaw
// takes it all, as there (2 atan2 of the quaternion's x and y, derived for each sign).
Vec3 euler_from_quaternion(const std::array<double, 4>& q) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double sin_pitch = 2.0 * (w * y - x * z);
  if (sin_pitch >= 0.99999) return {0.0, M_PI / 2, 2.0 * std::atan2(-x, y)};
  if (sin_pitch <= -0.99999) return {0.0, -M_PI / 2, 2.0 * std::atan2(x, -y)};
  const double roll = std::atan2(2.0 * (y * z + w * x), w * w - x * x - y * y + z * z);
  const double yaw = std::atan2(2.0 * (x * y + w * z), w * w + x * x - y * y - z * z);
  return {roll, std::asin(sin_pitch), yaw};
}

}  // namespace

GripperGoalEnv::GripperGoalEnv(GoalTask task, const Config& config)
    : task_(task),
      config_(config),
      dense_(config.reward_type == "dense"),
      scenario_(load_goal_task_scenario(
          config.scenario.empty() ? shipped_grasp_scenario(scenario_name(task)) : config.scenario)),
      observation_size_(observation_size_of(task)),
      action_space_(Space::box(-1.0f, 1.0f, {task == GoalTask::kPickAndPlace ? 4 : 3})),
      camera_(config.camera, id()) {
  if (config_.reward_type != "sparse" && config_.reward_type != "dense")
    throw std::invalid_argument(id() + ": reward_type is sparse or dense, not '" +
                                config_.reward_type + "'");
  if (!(config_.distance_threshold > 0) || !(config_.palm_force > 0) ||
      !(config_.finger_force > 0) || config_.substeps < 1 || config_.solver_iterations < 1)
    throw std::invalid_argument(id() +
                                ": distance_threshold, palm_force, finger_force, "
                                "substeps and solver_iterations must be positive");
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const Space state = Space::box(-kInf, kInf, {observation_size_});
  std::vector<std::pair<std::string, Space>> keys = {
      {"observation", camera_.uses_state() ? state : camera_.image_space()},
      {"achieved_goal", Space::box(-kInf, kInf, {3})},
      {"desired_goal", Space::box(-kInf, kInf, {3})}};
  if (camera_.uses_state() && camera_.uses_pixels())
    keys.push_back({"pixels", camera_.image_space()});
  observation_space_ = Space::dict(std::move(keys));
  for (size_t i = 0; i < observation_space_.keys().size(); ++i) {
    const std::string& key = observation_space_.keys()[i];
    const size_t at = static_cast<size_t>(observation_space_.offset(i));
    (key == "achieved_goal"  ? at_achieved_
     : key == "desired_goal" ? at_desired_
     : key == "pixels"       ? at_pixels_
                             : at_observation_) = at;
  }
  if (!camera_.uses_state()) at_pixels_ = at_observation_;
  key_success_ = info_.add_key("is_success");
  key_distance_ = info_.add_key("distance");
}

GripperGoalEnv::~GripperGoalEnv() = default;

std::string GripperGoalEnv::id() const {
  switch (task_) {
    case GoalTask::kReach: return "GripperReach-v0";
    case GoalTask::kPush: return "GripperPush-v0";
    case GoalTask::kPickAndPlace: return "GripperPickAndPlace-v0";
  }
  return "";
}

float GripperGoalEnv::distance(const float* a, const float* b) {
  // float32 throughout, like numpy's norm of panda-gym's float32 goals.
  const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

float GripperGoalEnv::reward_of(float d) const {
  // panda-gym: sparse -np.array(d > threshold, float32); dense -d.
  if (dense_) return -d;
  return d > static_cast<float>(config_.distance_threshold) ? -1.0f : 0.0f;
}

void GripperGoalEnv::compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                                    const Eigen::Ref<const Eigen::MatrixXf>& desired,
                                    Eigen::Ref<Eigen::RowVectorXf> rewards) const {
  if (achieved.rows() != 3 || desired.rows() != 3 || achieved.cols() != desired.cols() ||
      rewards.size() != achieved.cols())
    throw std::invalid_argument(id() + ": compute_reward takes 3 x n goals and n rewards");
  for (Eigen::Index j = 0; j < achieved.cols(); ++j) {
    const float a[3] = {achieved(0, j), achieved(1, j), achieved(2, j)};
    const float d[3] = {desired(0, j), desired(1, j), desired(2, j)};
    rewards[j] = reward_of(distance(a, d));
  }
}

Vec3 GripperGoalEnv::achieved_goal() const {
  return task_ == GoalTask::kReach ? world_->grasp_point() : world_->cube_position();
}

void GripperGoalEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  const GoalTaskScenario& s = scenario_;
  // Draws in a fixed order (cube, gripper, goal): the episode depends on the seed alone.
  GripperWorld::Layout layout;
  layout.with_cube = task_ != GoalTask::kReach;
  if (layout.with_cube) {
    layout.cube_size = draw(rng, s.cube.size);
    layout.cube_mass = draw(rng, s.cube.mass);
    layout.cube_friction = draw(rng, s.cube.friction);
    layout.cube_position = {draw(rng, s.cube.x), draw(rng, s.cube.y), layout.cube_size / 2};
    layout.cube_yaw = draw(rng, s.cube.yaw);
  }
  layout.grasp_point = {draw(rng, s.palm.x), draw(rng, s.palm.y), draw(rng, s.palm.z)};
  // panda-gym's neutral pose has the fingers closed (panda.py neutral_joint_values).
  layout.opening = 0.0;
  layout.palm_force = config_.palm_force;
  layout.finger_force = config_.finger_force;
  layout.solver_iterations = config_.solver_iterations;
  world_.reset();
  world_ = std::make_unique<GripperWorld>(layout);
  resting_height_ = layout.with_cube ? layout.cube_size / 2 : 0.0;

  const Vec3 start = achieved_goal();
  const float start_f[3] = {static_cast<float>(start[0]), static_cast<float>(start[1]),
                            static_cast<float>(start[2])};
  for (int attempt = 0;; ++attempt) {
    // Fetch's target_in_the_air: a coin first, the height only when it says "in the air".
    goal_ = {draw(rng, s.goal_x), draw(rng, s.goal_y), s.goal_z[0]};
    if (rng.uniform() < s.goal_in_air_probability) goal_[2] = draw(rng, s.goal_z);
    goal_[2] += resting_height_;  // Push, PickAndPlace: the cube's centre on the table
    const float goal_f[3] = {static_cast<float>(goal_[0]), static_cast<float>(goal_[1]),
                             static_cast<float>(goal_[2])};
    if (!s.goal_apart || distance(start_f, goal_f) >= config_.distance_threshold) break;
    if (attempt + 1 == kMaxGoalDraws)
      throw RuntimeFailure(id() + ": scenario '" + s.name +
                           "' draws no goal farther than "
                           "distance_threshold from the start in " +
                           std::to_string(kMaxGoalDraws) + " tries");
  }
  steps_ = 0;
  observe(obs);
}

float GripperGoalEnv::observe(std::span<float> obs) {
  write_observation(obs);
  // The reward and success from the goals as observed, exactly as compute_reward sees them.
  const float d = distance(&obs[at_achieved_], &obs[at_desired_]);
  success_ = d < static_cast<float>(config_.distance_threshold);
  info_.clear();
  info_.set(key_success_, success_ ? 1.0 : 0.0);
  info_.set(key_distance_, d);
  return d;
}

StepResult GripperGoalEnv::step(std::span<const float> action, std::span<float> obs) {
  if (!world_) throw std::logic_error(id() + ": call reset() before step()");
  if (action.size() != static_cast<size_t>(action_space_.flat_dim()))
    throw std::invalid_argument(id() + ": an action has " +
                                std::to_string(action_space_.flat_dim()) + " numbers");
  for (float a : action)
    if (!std::isfinite(a)) throw std::invalid_argument(id() + ": the action is not finite");
  const auto unit = [&](int i) { return std::clamp(static_cast<double>(action[i]), -1.0, 1.0); };
  using W = GoalWorkspace;
  const Vec3 at = world_->grasp_point();
  const Vec3 target{std::clamp(at[0] + kMovePerStep * unit(0), -W::kXY, W::kXY),
                    std::clamp(at[1] + kMovePerStep * unit(1), -W::kXY, W::kXY),
                    std::clamp(at[2] + kMovePerStep * unit(2), W::kBottom, W::kTop)};
  // Blocked fingers are held closed (panda.py: target_fingers_width = 0); free ones move
  // relative to their opening now.
  const double opening = blocked_gripper() ? 0.0 : world_->opening() + kGripPerStep * unit(3);
  world_->command(target, std::clamp(opening, 0.0, GripperWorld::kMaxOpening));
  world_->step(config_.substeps);
  ++steps_;
  const float d = observe(obs);
  StepResult result;
  result.reward = reward_of(d);
  result.terminated = config_.terminate_on_success && success_;
  result.truncated = steps_ >= scenario_.episode_steps;
  return result;
}

void GripperGoalEnv::write_observation(std::span<float> obs) {
  const GripperWorld& w = *world_;
  if (camera_.uses_pixels()) {
    camera_.write_image(w, {200, 40, 40}, obs.subspan(at_pixels_, camera_.image_floats()));
  }
  write_goals(obs);
  if (!camera_.uses_state()) return;
  size_t i = at_observation_;
  const auto put = [&](double v) { obs[i++] = static_cast<float>(v); };
  for (double v : w.grasp_point()) put(v);
  for (double v : w.palm_velocity()) put(v);  // the palm does not turn: the grasp point's
  if (!blocked_gripper()) put(w.opening());
  if (w.has_cube()) {
    for (double v : w.cube_position()) put(v);
    for (double v : euler_from_quaternion(w.cube_orientation())) put(v);
    for (double v : w.cube_velocity()) put(v);
    for (double v : w.cube_angular_velocity()) put(v);
  }
}

void GripperGoalEnv::write_goals(std::span<float> obs) const {
  const Vec3 achieved = achieved_goal();
  for (int k = 0; k < 3; ++k) {
    obs[at_achieved_ + k] = static_cast<float>(achieved[k]);
    obs[at_desired_ + k] = static_cast<float>(goal_[k]);
  }
}

}  // namespace rlrun
