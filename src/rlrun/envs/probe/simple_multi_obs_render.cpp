// SimpleMultiObsEnv-v0's picture: the 4x4 grid from above, row 0 at the top, walls dark, the
// goal green, the agent a blue disc.
#include <algorithm>
#include <array>
#include <stdexcept>

#include "rlrun/envs/probe/simple_multi_obs.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

void SimpleMultiObs::draw(int cell, Frame& frame) const {
  frame.begin_scene(kSide, kSide, {255, 255, 255}, /*y_up=*/false);
  for (int c = 0; c < kSide * kSide; ++c) {
    const double x = c % kSide, y = c / kSide;
    const std::array<Point, 4> square{Point{x + 0.03, y + 0.03}, Point{x + 0.97, y + 0.03},
                                      Point{x + 0.97, y + 0.97}, Point{x + 0.03, y + 0.97}};
    const Rgb color = is_wall(c)   ? Rgb{70, 70, 70}
                      : c == kGoal ? Rgb{120, 200, 120}
                                   : Rgb{235, 235, 235};
    frame.polygon(square, color);
  }
  frame.circle({cell % kSide + 0.5, cell / kSide + 0.5}, 0.3, {40, 90, 200});
  frame.end_scene();
}

bool SimpleMultiObs::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error("SimpleMultiObsEnv-v0: call reset() before render()");
  draw(state_, frame);
  return true;
}

bool SimpleMultiObs::render_observation(std::span<const float> obs, Frame& frame) const {
  if (!observation_space_.contains(obs))
    throw std::invalid_argument("SimpleMultiObsEnv-v0: an observation must be 10 values in " +
                                observation_space_.describe() + "; this one is not");
  // The column is the one whose vector the observation shows.
  const int row = static_cast<int>(obs[4]);
  for (int col = 0; col < kSide; ++col) {
    const auto& v = column_vectors_[static_cast<size_t>(col)];
    if (std::equal(v.begin(), v.end(), obs.begin() + 5)) {
      draw(row * kSide + col, frame);
      return true;
    }
  }
  throw std::invalid_argument(
      "SimpleMultiObsEnv-v0: the observation's 'vec' is none of this env's column vectors "
      "(logged with another vector_seed?)");
}

}  // namespace rlrun
