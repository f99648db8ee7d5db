// The identity envs' picture: one row per entry of the space. A categorical entry
// (Discrete, MultiDiscrete, a MultiBinary bit) is a row of cells, one per value; a Box entry a
// number line from low to high with the eps band. The state is green; the last action is a
// disc on its value, blue when it matched the state it answered, red when it did not.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "rlrun/core/plural.hpp"
#include "rlrun/envs/probe/identity_env.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

namespace {

constexpr double kSceneWidth = 10.0;
constexpr Rgb kCell{225, 225, 225}, kState{120, 200, 120}, kHit{40, 90, 200}, kMiss{200, 60, 60};

std::array<Point, 4> rect(double x0, double y0, double x1, double y1) {
  return {Point{x0, y0}, Point{x1, y0}, Point{x1, y1}, Point{x0, y1}};
}

// Values of entry i: its category count (0 for a Box entry) and the value of category 0.
std::pair<int64_t, int64_t> categories(const Space& space, size_t i) {
  switch (space.kind()) {
    case SpaceKind::kDiscrete: return {space.n(), space.start()};
    case SpaceKind::kMultiDiscrete: return {space.nvec()[i], 0};
    case SpaceKind::kMultiBinary: return {2, 0};
    default: return {0, 0};
  }
}

}  // namespace

RenderSpec IdentityEnv::render_spec() const {
  const int rows = observation_space_.flat_dim();
  return {480, std::clamp(60 * rows, 60, 960), 10.0};
}

void IdentityEnv::draw(std::span<const float> state, std::span<const float> action,
                       Frame& frame) const {
  const Space& space = observation_space_;
  const size_t rows = state.size();
  frame.begin_scene(kSceneWidth, static_cast<double>(rows), {255, 255, 255}, /*y_up=*/false);
  const bool hit = !action.empty() && matches(action, last_state_);
  for (size_t i = 0; i < rows; ++i) {
    const double y = static_cast<double>(i);
    const auto [n, start] = categories(space, i);
    if (n > 0) {
      const double w = kSceneWidth / static_cast<double>(n);
      for (int64_t k = 0; k < n; ++k) {
        const bool on = static_cast<int64_t>(state[i]) - start == k;
        frame.polygon(rect(k * w + 0.02, y + 0.1, (k + 1) * w - 0.02, y + 0.9),
                      on ? kState : kCell);
      }
      if (!action.empty()) {
        const double k = static_cast<double>(static_cast<int64_t>(action[i]) - start);
        frame.circle({(k + 0.5) * w, y + 0.5}, std::min(0.3, 0.3 * w), hit ? kHit : kMiss);
      }
      continue;
    }
    const double low = space.low()[i], high = space.high()[i];
    const auto x_of = [&](double v) {
      return 0.5 + (kSceneWidth - 1.0) * (std::clamp(v, low, high) - low) / (high - low);
    };
    frame.line({0.5, y + 0.5}, {kSceneWidth - 0.5, y + 0.5}, {90, 90, 90}, 0.04);
    frame.polygon(rect(x_of(state[i] - eps_), y + 0.3, x_of(state[i] + eps_), y + 0.7), kCell);
    frame.line({x_of(state[i]), y + 0.2}, {x_of(state[i]), y + 0.8}, kState, 0.12);
    if (!action.empty()) frame.circle({x_of(action[i]), y + 0.5}, 0.15, hit ? kHit : kMiss);
  }
  frame.end_scene();
}

bool IdentityEnv::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error(id_ + ": call reset() before render()");
  draw(state_, has_action_ ? std::span<const float>(last_action_) : std::span<const float>(),
       frame);
  return true;
}

bool IdentityEnv::render_observation(std::span<const float> obs, Frame& frame) const {
  if (!observation_space_.contains(obs))
    throw std::invalid_argument(id_ + ": an observation must be " +
                                count_of(observation_space_.flat_dim(), "value") + " in " +
                                observation_space_.describe() + "; this one is not");
  draw(obs, {}, frame);
  return true;
}

}  // namespace rlrun
