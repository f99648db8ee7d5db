#include "rlrun/envs/classic/classic_control_env.hpp"

#include <random>
#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

ClassicControlEnv::ClassicControlEnv(Space observation_space, Space action_space)
    : observation_space_(std::move(observation_space)), action_space_(std::move(action_space)) {}

void ClassicControlEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  if (seed) {
    rng_.reseed(*seed);
    ever_seeded_ = true;
  } else if (!ever_seeded_) {
    std::random_device device;
    rng_.reseed((static_cast<uint64_t>(device()) << 32) ^ device());
    ever_seeded_ = true;
  }
  info_.clear();
  sample_initial_state();
  has_state_ = true;
  write_observation(obs);
}

void ClassicControlEnv::set_state(std::span<const double> state, std::span<float> obs) {
  if (static_cast<int>(state.size()) != state_dim())
    throw std::invalid_argument(id() + ": set_state expects " + std::to_string(state_dim()) +
                                " values, got " + std::to_string(state.size()));
  load_state(state);
  has_state_ = true;
  write_observation(obs);
}

void ClassicControlEnv::require_reset() const {
  if (!has_state_) throw std::logic_error(id() + ": call reset() before step()");
}

int ClassicControlEnv::discrete_action(std::span<const float> action) const {
  if (!action_space_.contains(action))
    throw std::invalid_argument(
        id() + ": action " + (action.empty() ? std::string("<empty>") : std::to_string(action[0])) +
        " is not in " + action_space_.describe());
  return static_cast<int>(action[0]);
}

}  // namespace rlrun
