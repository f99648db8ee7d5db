#include "rlrun/env/discrete_action.hpp"
#include "rlrun/envs/classic/classic_control_env.hpp"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rlrun {

ClassicControlEnv::ClassicControlEnv(Space observation_space, Space action_space)
    : observation_space_(std::move(observation_space)), action_space_(std::move(action_space)) {}

void ClassicControlEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
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

void ClassicControlEnv::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  std::vector<double> state(static_cast<size_t>(state_dim()));
  get_state(state);
  out.put_vector("state", state);
  write_extra_state(out);
}

void ClassicControlEnv::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  // Extra state first: it may say how the physical state is stored (float32 or float64).
  read_extra_state(in);
  load_state(in.get_span<double>("state", state_dim()));
}

void ClassicControlEnv::require_reset() const {
  if (!has_state_) throw std::logic_error(id() + ": call reset() before step()");
}

int ClassicControlEnv::discrete_action(std::span<const float> action) const {
  return checked_discrete_action(action_space_, action, id());
}

}  // namespace rlrun
