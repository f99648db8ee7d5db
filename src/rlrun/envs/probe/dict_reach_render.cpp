// DictReach-v0's picture: the square [-1, 1]^2 from above, the goal a green disc inside its
// tolerance ring, the point a blue disc.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "rlrun/envs/probe/dict_reach.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

void DictReach::draw(std::span<const float> goal, std::span<const float> position,
                     Frame& frame) const {
  frame.begin_scene(2.2, 2.2, {255, 255, 255});
  const auto at = [](std::span<const float> p) { return Point{p[0] + 1.1, p[1] + 1.1}; };
  const Point square[] = {{0.1, 0.1}, {2.1, 0.1}, {2.1, 2.1}, {0.1, 2.1}, {0.1, 0.1}};
  frame.polyline(square, {90, 90, 90}, 0.01);
  frame.circle(at(goal), std::max(config_.goal_tolerance, 0.02), {200, 235, 200});
  frame.circle(at(goal), 0.025, {60, 160, 60});
  frame.circle(at(position), 0.04, {40, 90, 200});
  frame.end_scene();
}

bool DictReach::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error("DictReach-v0: call reset() before render()");
  draw(goal_, position_, frame);
  return true;
}

bool DictReach::render_observation(std::span<const float> obs, Frame& frame) const {
  if (!observation_space_.contains(obs))
    throw std::invalid_argument("DictReach-v0: an observation must be 4 values in " +
                                observation_space_.describe() + "; this one is not");
  draw(obs.subspan(0, 2), obs.subspan(2, 2), frame);
  return true;
}

}  // namespace rlrun
