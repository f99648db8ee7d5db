#include "rlrun/envs/probe/dict_reach.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

namespace {
// Flat layout of the observation (rlrun/space.hpp: keys in sorted order).
constexpr size_t kGoal = 0, kPosition = 2;
}  // namespace

DictReach::DictReach(const Config& config) : config_(config) {
  if (!(config_.step_size > 0) || !(config_.goal_tolerance > 0))
    throw std::invalid_argument("DictReach-v0: step_size and goal_tolerance must be > 0");
  observation_space_ = Space::dict(
      {{"position", Space::box(-1.0f, 1.0f, {2})}, {"goal", Space::box(-1.0f, 1.0f, {2})}});
  action_space_ = Space::box(-1.0f, 1.0f, {2});
  id_ = "DictReach-v0";
  key_success_ = info_.add_key("is_success");
  key_distance_ = info_.add_key("distance");
}

double DictReach::distance() const {
  return std::hypot(static_cast<double>(position_[0]) - goal_[0],
                    static_cast<double>(position_[1]) - goal_[1]);
}

void DictReach::write_observation(std::span<float> obs) const {
  std::copy(goal_.begin(), goal_.end(), obs.begin() + kGoal);
  std::copy(position_.begin(), position_.end(), obs.begin() + kPosition);
}

void DictReach::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  for (float& v : position_) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  for (float& v : goal_) v = static_cast<float>(rng.uniform(-1.0, 1.0));
  has_state_ = true;
  info_.clear();
  info_.set(key_success_, 0.0);
  info_.set(key_distance_, distance());
  write_observation(obs);
}

StepResult DictReach::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("DictReach-v0: call reset() before step()");
  if (action.size() != 2 || !std::isfinite(action[0]) || !std::isfinite(action[1]))
    throw std::invalid_argument("DictReach-v0: the action must be 2 finite values");
  for (size_t i = 0; i < 2; ++i) {
    const double move = config_.step_size * std::clamp(static_cast<double>(action[i]), -1.0, 1.0);
    position_[i] = static_cast<float>(std::clamp(position_[i] + move, -1.0, 1.0));
  }
  const double d = distance();
  StepResult result;
  result.reward = -d;
  result.terminated = d < config_.goal_tolerance;
  info_.clear();
  info_.set(key_success_, result.terminated ? 1.0 : 0.0);
  info_.set(key_distance_, d);
  write_observation(obs);
  return result;
}

void DictReach::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_span<float>("goal", goal_);
  out.put_span<float>("position", position_);
}

void DictReach::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  in.get_into<float>("goal", goal_);
  in.get_into<float>("position", position_);
  for (float v : {goal_[0], goal_[1], position_[0], position_[1]})
    if (!(v >= -1.0f && v <= 1.0f))
      throw StateMismatch("DictReach-v0: a saved position is outside [-1, 1]^2");
}

}  // namespace rlrun
