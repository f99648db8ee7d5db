#include "rlrun/envs/probe/bit_flipping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

BitFlipping::BitFlipping(const Config& config) : config_(config) {
  if (config_.n_bits < 1 || config_.max_steps < 0)
    throw std::invalid_argument("BitFlippingEnv-v0: n_bits must be >= 1 and max_steps >= 0");
  if (config_.max_steps == 0) config_.max_steps = config_.n_bits;
  const Space bits = Space::multi_binary(config_.n_bits);
  observation_space_ =
      Space::dict({{"observation", bits}, {"achieved_goal", bits}, {"desired_goal", bits}});
  action_space_ = config_.continuous ? Space::box(-1.0f, 1.0f, {config_.n_bits})
                                     : Space::discrete(config_.n_bits);
  id_ = "BitFlippingEnv-v0";
  key_success_ = info_.add_key("is_success");
  state_.assign(static_cast<size_t>(config_.n_bits), 0.0f);
}

void BitFlipping::write_observation(std::span<float> obs) const {
  // Flat order: achieved_goal, desired_goal, observation (keys sorted, rlrun/space.hpp).
  const size_t n = state_.size();
  std::copy(state_.begin(), state_.end(), obs.begin());
  std::fill(obs.begin() + static_cast<std::ptrdiff_t>(n),
            obs.begin() + static_cast<std::ptrdiff_t>(2 * n), 1.0f);
  std::copy(state_.begin(), state_.end(), obs.begin() + static_cast<std::ptrdiff_t>(2 * n));
}

void BitFlipping::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  for (float& bit : state_) bit = static_cast<float>(rng.below(2));
  steps_ = 0;
  has_state_ = true;
  info_.clear();
  info_.set(key_success_, 0.0);
  write_observation(obs);
}

StepResult BitFlipping::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("BitFlippingEnv-v0: call reset() before step()");
  const size_t n = state_.size();
  if (config_.continuous) {
    if (action.size() != n) throw std::invalid_argument("BitFlippingEnv-v0: action size");
    for (size_t i = 0; i < n; ++i)
      if (action[i] > 0.0f) state_[i] = 1.0f - state_[i];
  } else {
    if (action.size() != 1 || !(action[0] >= 0.0f) || !(action[0] < static_cast<float>(n)))
      throw std::invalid_argument("BitFlippingEnv-v0: action must be a bit index below " +
                                  std::to_string(n));
    const size_t i = static_cast<size_t>(action[0]);
    state_[i] = 1.0f - state_[i];
  }
  ++steps_;
  write_observation(obs);
  StepResult result;
  const bool reached = std::all_of(state_.begin(), state_.end(), [](float b) { return b == 1.0f; });
  result.reward = reached ? 0.0 : -1.0;
  result.terminated = reached;  // SB3: terminated = reward == 0
  result.truncated = steps_ >= config_.max_steps;
  info_.clear();
  info_.set(key_success_, reached ? 1.0 : 0.0);
  return result;
}

void BitFlipping::compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                                 const Eigen::Ref<const Eigen::MatrixXf>& desired,
                                 Eigen::Ref<Eigen::RowVectorXf> rewards) const {
  // SB3: -(|achieved - desired| > 0)
  for (Eigen::Index j = 0; j < achieved.cols(); ++j)
    rewards(j) = (achieved.col(j).array() == desired.col(j).array()).all() ? 0.0f : -1.0f;
}

void BitFlipping::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_int("steps", steps_);
  out.put_span<float>("state", state_);
}

void BitFlipping::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  const int64_t steps = in.get_int("steps");
  if (steps < 0 || steps > config_.max_steps)
    throw StateMismatch("BitFlippingEnv-v0: bad step count");
  steps_ = static_cast<int>(steps);
  in.get_into<float>("state", state_);
  for (float b : state_)
    if (b != 0.0f && b != 1.0f) throw StateMismatch("BitFlippingEnv-v0: a bit that is not 0 or 1");
}

}  // namespace rlrun
