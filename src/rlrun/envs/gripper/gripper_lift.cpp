#include "rlrun/envs/gripper/gripper_lift.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rlrun {

namespace {

// Where the grasp point may be sent: above the table's central 30 cm square (the spawn area
// and a margin), the finger tips above the table top.
constexpr double kWorkspaceXY = 0.15;
constexpr double kMinGraspHeight = 0.012;  // m: the finger tips 3 mm above the table
constexpr double kMaxGraspHeight = 0.2;    // m: within the camera's view

double draw(Rng& rng, const std::vector<double>& range) { return rng.uniform(range[0], range[1]); }

}  // namespace

GripperLift::GripperLift(const Config& config, bool easy)
    : config_(config),
      easy_(easy),
      scenario_(load_grasp_scenario(config.scenario.empty()
                                        ? shipped_grasp_scenario(easy ? "lift_easy" : "lift")
                                        : config.scenario)),
      camera_(config.camera, easy ? "GripperLiftEasy-v0" : "GripperLift-v0"),
      observation_space_(
          camera_.space(Space::box(-std::numeric_limits<float>::infinity(),
                                   std::numeric_limits<float>::infinity(), {kObsSize}))),
      action_space_(Space::box(-1.0f, 1.0f, {4})) {
  if (!(config_.palm_force > 0) || !(config_.finger_force > 0) || config_.substeps < 1 ||
      config_.solver_iterations < 1)
    throw std::invalid_argument(id() +
                                ": palm_force, finger_force, substeps and "
                                "solver_iterations must be positive");
  key_success_ = info_.add_key("is_success");
  key_grasped_ = info_.add_key("grasped");
  key_lift_ = info_.add_key("lift");
  key_distance_ = info_.add_key("distance");
}

GripperLift::~GripperLift() = default;

void GripperLift::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  // Draws in a fixed order: the episode depends on the seed alone.
  GripperWorld::Layout layout;
  layout.cube_size = draw(rng, scenario_.cube.size);
  layout.cube_mass = draw(rng, scenario_.cube.mass);
  layout.cube_friction = draw(rng, scenario_.cube.friction);
  layout.cube_position = {draw(rng, scenario_.cube.x), draw(rng, scenario_.cube.y),
                          layout.cube_size / 2};
  layout.cube_yaw = draw(rng, scenario_.cube.yaw);
  Vec3 start{draw(rng, scenario_.palm.x), draw(rng, scenario_.palm.y), draw(rng, scenario_.palm.z)};
  if (scenario_.palm_above_cube) {
    start[0] += layout.cube_position[0];
    start[1] += layout.cube_position[1];
    start[2] += layout.cube_size;
  }
  layout.grasp_point = start;
  layout.opening = GripperWorld::kMaxOpening;
  layout.palm_force = config_.palm_force;
  layout.finger_force = config_.finger_force;
  layout.solver_iterations = config_.solver_iterations;
  world_.reset();
  world_ = std::make_unique<GripperWorld>(layout);
  resting_height_ = layout.cube_size / 2;
  last_opening_ = world_->opening();
  opening_rate_ = 0;
  steps_ = 0;
  reward_and_success();
  write_observation(obs);
}

StepResult GripperLift::step(std::span<const float> action, std::span<float> obs) {
  if (!world_) throw std::logic_error(id() + ": call reset() before step()");
  if (action.size() != 4) throw std::invalid_argument(id() + ": an action has 4 numbers");
  const auto unit = [&](int i) { return std::clamp(static_cast<double>(action[i]), -1.0, 1.0); };
  const Vec3 at = world_->grasp_point();
  const Vec3 target{std::clamp(at[0] + kMovePerStep * unit(0), -kWorkspaceXY, kWorkspaceXY),
                    std::clamp(at[1] + kMovePerStep * unit(1), -kWorkspaceXY, kWorkspaceXY),
                    std::clamp(at[2] + kMovePerStep * unit(2), kMinGraspHeight, kMaxGraspHeight)};
  world_->command(target, GripperWorld::kMaxOpening * (1.0 - unit(3)) / 2);
  world_->step(config_.substeps);
  const double opening = world_->opening();
  opening_rate_ = (opening - last_opening_) / (config_.substeps * GripperWorld::kTimeStep);
  last_opening_ = opening;
  ++steps_;
  StepResult result;
  result.reward = reward_and_success();
  result.truncated = steps_ >= scenario_.episode_steps;
  write_observation(obs);
  return result;
}

double GripperLift::reward_and_success() {
  const Vec3 cube = world_->cube_position(), grasp = world_->grasp_point();
  const double d = std::sqrt((cube[0] - grasp[0]) * (cube[0] - grasp[0]) +
                             (cube[1] - grasp[1]) * (cube[1] - grasp[1]) +
                             (cube[2] - grasp[2]) * (cube[2] - grasp[2]));
  touching_ = world_->finger_contacts();  // once per step: the observation reuses it
  const bool grasped = touching_[0] && touching_[1];
  const double rise = cube[2] - resting_height_;
  success_ = grasped && rise >= kLiftHeight;
  info_.set(key_success_, success_ ? 1.0 : 0.0);
  info_.set(key_grasped_, grasped ? 1.0 : 0.0);
  info_.set(key_lift_, rise);
  info_.set(key_distance_, d);
  if (success_) return 2.25;
  double reward = 1.0 - std::tanh(10.0 * d);
  if (grasped) reward += 0.25 + std::clamp(rise / kLiftHeight, 0.0, 1.0);
  return reward;
}

void GripperLift::write_observation(std::span<float> all) {
  const GripperWorld& w = *world_;
  // The camera sees the cube red always (the render's green on success is an annotation).
  camera_.write_pixels(w, Rgb{200, 40, 40}, all, observation_space_);
  if (!camera_.uses_state()) return;
  const std::span<float> obs = camera_.state_part(all, observation_space_);
  const Vec3 grasp = w.grasp_point(), palm_velocity = w.palm_velocity();
  const Vec3 cube = w.cube_position(), velocity = w.cube_velocity(),
             spin = w.cube_angular_velocity();
  const auto q = w.cube_orientation();
  int i = 0;
  const auto put = [&](double v) { obs[i++] = static_cast<float>(v); };
  for (double v : grasp) put(v);
  for (double v : palm_velocity) put(v);
  put(w.opening());
  put(opening_rate_);
  for (double v : cube) put(v);
  for (double v : q) put(v);
  for (double v : velocity) put(v);
  for (double v : spin) put(v);
  for (int k = 0; k < 3; ++k) put(cube[k] - grasp[k]);
  put(touching_[0] ? 1.0 : 0.0);
  put(touching_[1] ? 1.0 : 0.0);
}

}  // namespace rlrun
