// ClassicControlEnv's rendering entry points; each env's picture is in <env>_render.cpp.
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

#include "rlrun/core/plural.hpp"
#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

bool ClassicControlEnv::render(Frame& frame) const {
  // Gymnasium's render() draws nothing before the first reset (state is None).
  if (!has_state_) throw std::logic_error(id() + ": call reset() before render()");
  spec_.draw(std::span<const double>(state_.data(), static_cast<size_t>(state_dim())), last_action_,
             frame);
  return true;
}

bool ClassicControlEnv::render_observation(std::span<const float> obs, Frame& frame) const {
  if (static_cast<int>(obs.size()) != observation_space_.flat_dim())
    throw std::invalid_argument(id() + ": an observation has " +
                                count_of(observation_space_.flat_dim(), "value") + ", got " +
                                std::to_string(obs.size()));
  std::array<double, kMaxStateDim> state{};
  const std::span<double> s(state.data(), static_cast<size_t>(state_dim()));
  spec_.state_from_observation(obs, s);
  spec_.draw(s, std::numeric_limits<double>::quiet_NaN(), frame);
  return true;
}

}  // namespace rlrun
