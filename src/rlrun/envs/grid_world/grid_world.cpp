#include "rlrun/envs/grid_world/grid_world.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/discrete_action.hpp"

#include <limits>
#include <stdexcept>

namespace rlrun {

GridWorld::GridWorld(const Config& config)
    : config_(config),
      observation_space_(Space::multi_discrete(
          {config.size > 0 ? config.size : 1, config.size > 0 ? config.size : 1})),
      action_space_(Space::discrete(kNumActions)) {
  if (config_.size < 2) throw std::invalid_argument("GridWorld-v0: size must be >= 2");
  if (config_.max_steps < 1) throw std::invalid_argument("GridWorld-v0: max_steps must be >= 1");
  key_success_ = info_.add_key("is_success");
  key_bumped_ = info_.add_key("bumped");
  for (int a = 0; a < kNumActions; ++a) key_mask_[a] = info_.add_key(action_mask_key(a));
}

void GridWorld::write_info(bool at_goal, bool bumped) {
  info_.clear();
  info_.set(key_success_, at_goal ? 1.0 : 0.0);
  info_.set(key_bumped_, bumped ? 1.0 : 0.0);
  // The moves that stay on the grid; every cell has at least two.
  info_.set(key_mask_[kUp], row_ > 0 ? 1.0 : 0.0);
  info_.set(key_mask_[kRight], col_ < config_.size - 1 ? 1.0 : 0.0);
  info_.set(key_mask_[kDown], row_ < config_.size - 1 ? 1.0 : 0.0);
  info_.set(key_mask_[kLeft], col_ > 0 ? 1.0 : 0.0);
}

int GridWorld::shortest_path_length(int row, int col) const {
  return (config_.size - 1 - row) + (config_.size - 1 - col);
}

void GridWorld::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  // Gymnasium seeding (gymnasium/core.py Env.reset; env/env_seeding.hpp), as every rlrun env.
  seeding_.on_reset(seed);
  row_ = col_ = 0;
  if (config_.random_start) {
    // Cells in row-major order; the goal is the last one, so [0, n - 1) excludes it.
    const auto cells = static_cast<uint64_t>(config_.size * config_.size - 1);
    const int cell = static_cast<int>(seeding_.rng().below(cells));
    row_ = cell / config_.size;
    col_ = cell % config_.size;
  }
  steps_ = 0;
  has_state_ = true;
  write_info(false, false);
  write_observation(obs);
}

StepResult GridWorld::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("GridWorld-v0: call reset() before step()");
  const int chosen = checked_discrete_action(action_space_, action, "GridWorld-v0");
  int row = row_, col = col_;
  switch (chosen) {
    case kUp: --row; break;
    case kRight: ++col; break;
    case kDown: ++row; break;
    case kLeft: --col; break;
    default: break;
  }
  const bool bumped = row < 0 || row >= config_.size || col < 0 || col >= config_.size;
  if (!bumped) {
    row_ = row;
    col_ = col;
  }
  ++steps_;
  StepResult result;
  result.reward = bumped ? config_.wall_reward : config_.move_reward;
  const bool at_goal = row_ == config_.size - 1 && col_ == config_.size - 1;
  if (at_goal) {
    result.reward += config_.goal_reward;
    result.terminated = true;
  } else if (steps_ >= config_.max_steps) {
    result.reward += config_.timeout_reward;
    result.truncated = true;
  }
  write_info(at_goal, bumped);
  write_observation(obs);
  return result;
}

void GridWorld::write_observation(std::span<float> obs) const {
  obs[0] = static_cast<float>(row_);
  obs[1] = static_cast<float>(col_);
}

void GridWorld::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_int("row", row_);
  out.put_int("col", col_);
  out.put_int("steps", steps_);
}

void GridWorld::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  row_ = static_cast<int>(in.get_int_in("row", 0, config_.size - 1));
  col_ = static_cast<int>(in.get_int_in("col", 0, config_.size - 1));
  steps_ = static_cast<int>(in.get_int_in("steps", 0, std::numeric_limits<int>::max()));
  write_info(false, false);  // the restored cell's mask
}

}  // namespace rlrun
