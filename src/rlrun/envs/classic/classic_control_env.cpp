#include "rlrun/envs/classic/classic_control_env.hpp"

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/env/discrete_action.hpp"

namespace rlrun {

ClassicControlEnv::ClassicControlEnv(const ClassicSpec& spec, Space observation_space,
                                     Space action_space)
    : observation_space_(std::move(observation_space)),
      action_space_(std::move(action_space)),
      spec_(spec) {}

void ClassicControlEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  info_.clear();
  state_is_float32_ = spec_.initial_state(
      np_random(), std::span<double>(state_.data(), static_cast<size_t>(state_dim())));
  last_action_ = std::numeric_limits<double>::quiet_NaN();  // e.g. pendulum.py's last_u = None
  reset_bookkeeping();
  has_state_ = true;
  write_observation(obs);
}

void ClassicControlEnv::get_state(std::span<double> state) const {
  for (int i = 0; i < state_dim(); ++i) state[i] = state_[i];
}

void ClassicControlEnv::set_state(std::span<const double> state, std::span<float> obs) {
  if (static_cast<int>(state.size()) != state_dim())
    throw std::invalid_argument(id() + ": set_state expects " + std::to_string(state_dim()) +
                                " values, got " + std::to_string(state.size()));
  // An in-place `state[:] = values` keeps the array's dtype.
  for (int i = 0; i < state_dim(); ++i)
    state_[i] = state_is_float32_ ? static_cast<float>(state[i]) : state[i];
  has_state_ = true;
  write_observation(obs);
}

void ClassicControlEnv::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_vector("state", std::vector<double>(state_.begin(), state_.begin() + state_dim()));
  if (spec_.tracks_float32_state) out.put_bool("state_is_float32", state_is_float32_);
  write_extra_state(out);
}

void ClassicControlEnv::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  if (spec_.tracks_float32_state) state_is_float32_ = in.get_bool("state_is_float32");
  read_extra_state(in);
  const std::vector<double> state = in.get_span<double>("state", state_dim());
  for (int i = 0; i < state_dim(); ++i) state_[i] = state[i];
}

void ClassicControlEnv::require_reset() const {
  if (!has_state_) throw std::logic_error(id() + ": call reset() before step()");
}

int ClassicControlEnv::discrete_action(std::span<const float> action) const {
  return checked_discrete_action(action_space_, action, id());
}

}  // namespace rlrun
