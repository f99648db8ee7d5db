// ClassicControlEnv's rendering entry points; each env's picture is in <env>_render.cpp.
#include <array>
#include <stdexcept>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

namespace {
constexpr int kMaxStateDim = 8;
}  // namespace

bool ClassicControlEnv::render(Frame& frame) const {
  // Gymnasium's render() draws nothing before the first reset (state is None).
  if (!has_state_) throw std::logic_error(id() + ": call reset() before render()");
  std::array<double, kMaxStateDim> state{};
  const std::span<double> s(state.data(), static_cast<size_t>(state_dim()));
  get_state(s);
  draw_state(s, true, frame);
  return true;
}

bool ClassicControlEnv::render_observation(std::span<const float> obs, Frame& frame) const {
  if (static_cast<int>(obs.size()) != observation_space_.flat_dim())
    throw std::invalid_argument(id() + ": an observation has " +
                                std::to_string(observation_space_.flat_dim()) + " values, got " +
                                std::to_string(obs.size()));
  std::array<double, kMaxStateDim> state{};
  const std::span<double> s(state.data(), static_cast<size_t>(state_dim()));
  state_from_observation(obs, s);
  draw_state(s, false, frame);
  return true;
}

}  // namespace rlrun
