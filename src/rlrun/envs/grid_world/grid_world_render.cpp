// GridWorld-v0's picture: the grid seen from above with row 0 at the top, the goal cell
// green and the agent a blue disc.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rlrun/envs/grid_world/grid_world.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

void GridWorld::draw(int row, int col, Frame& frame) const {
  const double n = config_.size;
  frame.begin_scene(n, n, {255, 255, 255}, /*y_up=*/false);
  const auto cell = [](double r, double c, double inset) {
    return std::array<Point, 4>{Point{c + inset, r + inset}, Point{c + 1 - inset, r + inset},
                                Point{c + 1 - inset, r + 1 - inset},
                                Point{c + inset, r + 1 - inset}};
  };
  frame.polygon(cell(n - 1, n - 1, 0.0), {120, 200, 120});
  for (int i = 0; i <= config_.size; ++i) {
    frame.line({0, static_cast<double>(i)}, {n, static_cast<double>(i)}, {90, 90, 90}, 0.03);
    frame.line({static_cast<double>(i), 0}, {static_cast<double>(i), n}, {90, 90, 90}, 0.03);
  }
  frame.circle({col + 0.5, row + 0.5}, 0.3, {40, 90, 200});
  frame.end_scene();
}

bool GridWorld::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error("GridWorld-v0: call reset() before render()");
  draw(row_, col_, frame);
  return true;
}

bool GridWorld::render_observation(std::span<const float> obs, Frame& frame) const {
  if (obs.size() != 2)
    throw std::invalid_argument("GridWorld-v0: an observation has 2 values, got " +
                                std::to_string(obs.size()));
  draw(static_cast<int>(std::lround(obs[0])), static_cast<int>(std::lround(obs[1])), frame);
  return true;
}

}  // namespace rlrun
