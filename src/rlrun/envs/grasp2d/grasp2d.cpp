#include "rlrun/envs/grasp2d/grasp2d.hpp"
#include "rlrun/env/discrete_action.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {

// Positions are sums of step_size multiples, so a move meant to end exactly on the border
// can land a rounding error beyond it; that is not leaving the workspace.
constexpr double kBorderTolerance = 1e-9;

void check_position(const std::vector<double>& p, const char* name) {
  if (p.empty()) return;
  if (p.size() != 2 || !(p[0] >= 0.0 && p[0] <= 1.0 && p[1] >= 0.0 && p[1] <= 1.0))
    throw std::invalid_argument(std::string("Grasp2D-v0: ") + name +
                                " must be [x, y] inside [0, 1]^2 (or [] for random)");
}

}  // namespace

Grasp2D::Grasp2D(const Config& config)
    : config_(config),
      observation_space_(Space::box(0.0f, 1.0f, {6})),
      action_space_(Space::discrete(kNumActions)) {
  if (!(config_.step_size > 0.0 && config_.step_size <= 1.0))
    throw std::invalid_argument("Grasp2D-v0: step_size must be in (0, 1]");
  if (!(config_.success_threshold > 0.0))
    throw std::invalid_argument("Grasp2D-v0: success_threshold must be positive");
  if (!(config_.spawn_margin >= 0.0 && config_.spawn_margin <= 0.5))
    throw std::invalid_argument("Grasp2D-v0: spawn_margin must be in [0, 0.5]");
  check_position(config_.arm_start, "arm_start");
  check_position(config_.object_start, "object_start");
  key_success_ = info_.add_key("is_success");
  key_failure_ = info_.add_key("is_failure");
  key_action_ = info_.add_key("action");
  key_distance_ = info_.add_key("distance");
}

const char* Grasp2D::action_name(int action) {
  static constexpr const char* kNames[kNumActions] = {"left", "right", "up",
                                                      "down", "open",  "close"};
  return action >= 0 && action < kNumActions ? kNames[action] : "none";
}

double Grasp2D::distance() const { return std::hypot(arm_x_ - object_x_, arm_y_ - object_y_); }

void Grasp2D::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  ResetOptions options;
  if (!config_.arm_start.empty()) options.arm = {config_.arm_start[0], config_.arm_start[1]};
  if (!config_.object_start.empty())
    options.object = {config_.object_start[0], config_.object_start[1]};
  reset(seed, options, obs);
}

void Grasp2D::reset(std::optional<uint64_t> seed, const ResetOptions& options,
                    std::span<float> obs) {
  // Gymnasium seeding (gymnasium/core.py Env.reset; env/env_seeding.hpp).
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  const double lo = config_.spawn_margin, hi = 1.0 - config_.spawn_margin;
  arm_x_ = rng.uniform(lo, hi);
  arm_y_ = rng.uniform(lo, hi);
  object_x_ = rng.uniform(lo, hi);
  object_y_ = rng.uniform(lo, hi);
  if (options.arm) {
    arm_x_ = (*options.arm)[0];
    arm_y_ = (*options.arm)[1];
  }
  if (options.object) {
    object_x_ = (*options.object)[0];
    object_y_ = (*options.object)[1];
  }
  gripper_closed_ = false;
  grasped_ = false;
  last_action_ = -1;
  has_state_ = true;
  info_.clear();
  info_.set(key_success_, 0.0);
  info_.set(key_failure_, 0.0);
  info_.set(key_distance_, distance());
  write_observation(obs);
}

StepResult Grasp2D::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("Grasp2D-v0: call reset() before step()");
  const int a = checked_discrete_action(action_space_, action, "Grasp2D-v0");
  last_action_ = a;
  double dx = 0.0, dy = 0.0;
  switch (a) {
    case kLeft: dx = -config_.step_size; break;
    case kRight: dx = config_.step_size; break;
    case kUp: dy = config_.step_size; break;
    case kDown: dy = -config_.step_size; break;
    case kOpen: gripper_closed_ = false; break;
    case kClose: gripper_closed_ = true; break;
    default: break;
  }
  arm_x_ += dx;
  arm_y_ += dy;
  const bool outside = arm_x_ < -kBorderTolerance || arm_x_ > 1.0 + kBorderTolerance ||
                       arm_y_ < -kBorderTolerance || arm_y_ > 1.0 + kBorderTolerance;
  // The arm stops at the border it crossed, so the observation stays inside Box(0, 1).
  arm_x_ = std::clamp(arm_x_, 0.0, 1.0);
  arm_y_ = std::clamp(arm_y_, 0.0, 1.0);
  const double d = distance();
  // Closing counts as a grasp whenever the object is within reach, whether or not the
  // gripper was already closed (the course env checks the distance on every close).
  grasped_ = a == kClose && d <= config_.success_threshold;

  StepResult result;
  if (grasped_) {
    result.reward = config_.success_reward;
    result.terminated = true;
  } else if (outside) {
    result.reward = -config_.failure_penalty;
    result.terminated = true;
  } else {
    result.reward = -config_.step_penalty - config_.distance_scale * d;
  }
  info_.clear();
  info_.set(key_success_, grasped_ ? 1.0 : 0.0);
  info_.set(key_failure_, outside ? 1.0 : 0.0);
  info_.set(key_action_, a);
  info_.set(key_distance_, d);
  write_observation(obs);
  return result;
}

void Grasp2D::write_observation(std::span<float> obs) const {
  obs[0] = static_cast<float>(arm_x_);
  obs[1] = static_cast<float>(arm_y_);
  obs[2] = static_cast<float>(object_x_);
  obs[3] = static_cast<float>(object_y_);
  obs[4] = gripper_closed_ ? 1.0f : 0.0f;
  obs[5] = grasped_ ? 1.0f : 0.0f;
}

void Grasp2D::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  const std::vector<double> positions{arm_x_, arm_y_, object_x_, object_y_};
  out.put_vector("positions", positions);
  out.put_bool("gripper_closed", gripper_closed_);
  out.put_bool("grasped", grasped_);
  out.put_int("last_action", last_action_);
}

void Grasp2D::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  const std::vector<double> p = in.get_span<double>("positions", 4);
  arm_x_ = p[0];
  arm_y_ = p[1];
  object_x_ = p[2];
  object_y_ = p[3];
  gripper_closed_ = in.get_bool("gripper_closed");
  grasped_ = in.get_bool("grasped");
  last_action_ = static_cast<int>(in.get_int_in("last_action", -1, 5));
}

}  // namespace rlrun
