#include "rlrun/envs/probe/identity_env.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rlrun {

IdentityEnv::IdentityEnv(const Space& space, std::string id, double eps) : eps_(eps) {
  observation_space_ = space;
  action_space_ = space;
  id_ = std::move(id);
  state_.assign(static_cast<size_t>(space.flat_dim()), 0.0f);
  last_state_ = state_;
  last_action_ = state_;
}

void IdentityEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  // SB3 _choose_next_state: the next state is a sample of the space.
  observation_space_.sample(seeding_.rng(), state_);
  has_state_ = true;
  has_action_ = false;
  info_.clear();
  std::copy(state_.begin(), state_.end(), obs.begin());
}

bool IdentityEnv::matches(std::span<const float> action, std::span<const float> state) const {
  for (size_t i = 0; i < state.size(); ++i) {
    // SB3: np.all(state == action); IdentityEnvBox: state - eps <= action <= state + eps.
    const bool hit = action_space_.is_box()
                         ? std::abs(static_cast<double>(action[i]) - state[i]) <= eps_
                         : action[i] == state[i];
    if (!hit) return false;
  }
  return true;
}

StepResult IdentityEnv::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error(id_ + ": call reset() before step()");
  if (action.size() != state_.size() ||
      (!action_space_.is_box() && !action_space_.contains(action)))
    throw std::invalid_argument(id_ + ": the action is not in " + action_space_.describe());
  StepResult result;
  const bool hit = matches(action, state_);
  result.reward = hit ? 1.0 : 0.0;
  last_state_ = state_;
  std::copy(action.begin(), action.end(), last_action_.begin());
  has_action_ = true;
  observation_space_.sample(seeding_.rng(), state_);
  info_.clear();
  std::copy(state_.begin(), state_.end(), obs.begin());
  return result;
}

void IdentityEnv::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_bool("has_action", has_action_);
  out.put_vector("state", state_);
  out.put_vector("last_state", last_state_);
  out.put_vector("last_action", last_action_);
}

void IdentityEnv::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  has_action_ = in.get_bool("has_action");
  in.get_into<float>("state", state_);
  in.get_into<float>("last_state", last_state_);
  in.get_into<float>("last_action", last_action_);
  if (has_state_ && !observation_space_.contains(state_))
    throw StateMismatch(id_ + ": the saved state is not in " + observation_space_.describe());
}

IdentityDiscrete::IdentityDiscrete(const Config& config)
    : IdentityEnv(Space::discrete(config.dim), "IdentityEnv-v0") {}

namespace {
Space identity_box(const IdentityBox::Config& config) {
  if (!(config.low < config.high))
    throw std::invalid_argument("IdentityEnvBox-v0: low must be < high");
  return Space::box(static_cast<float>(config.low), static_cast<float>(config.high), {1});
}
}  // namespace

IdentityBox::IdentityBox(const Config& config)
    : IdentityEnv(identity_box(config), "IdentityEnvBox-v0", config.eps) {}

IdentityMultiDiscrete::IdentityMultiDiscrete(const Config& config)
    : IdentityEnv(Space::multi_discrete({config.dim, config.dim}), "IdentityEnvMultiDiscrete-v0") {}

IdentityMultiBinary::IdentityMultiBinary(const Config& config)
    : IdentityEnv(Space::multi_binary(config.dim), "IdentityEnvMultiBinary-v0") {}

}  // namespace rlrun
