// Grasp2D-v0's picture: the workspace [0,1]^2 seen from above, y up. The object is a red
// square inside a pale ring of radius success_threshold (where closing grasps it); the arm is
// a blue disc between two gripper jaws, drawn apart when open, together when closed, and
// green once the object is grasped.
#include <stdexcept>
#include <string>

#include "rlrun/envs/grasp2d/grasp2d.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

namespace {

struct Picture {
  double arm_x, arm_y, object_x, object_y;
  bool closed, grasped;
};

void draw(const Picture& p, double threshold, Frame& frame) {
  constexpr double kMargin = 0.05;  // scene border around the workspace
  constexpr double kSize = 1.0 + 2 * kMargin;
  auto at = [](double x, double y) { return Point{x + kMargin, y + kMargin}; };
  frame.begin_scene(kSize, kSize, {225, 225, 225});
  const Point workspace[] = {at(0, 0), at(0, 1), at(1, 1), at(1, 0)};
  frame.polygon(workspace, {255, 255, 255});
  frame.polyline(std::span<const Point>(workspace), {120, 120, 120}, 0.004);
  frame.line(at(0, 0), at(1, 0), {120, 120, 120}, 0.004);  // close the outline

  frame.circle(at(p.object_x, p.object_y), threshold, {220, 240, 220});
  constexpr double kHalfObject = 0.02;
  const Point object[] = {at(p.object_x - kHalfObject, p.object_y - kHalfObject),
                          at(p.object_x - kHalfObject, p.object_y + kHalfObject),
                          at(p.object_x + kHalfObject, p.object_y + kHalfObject),
                          at(p.object_x + kHalfObject, p.object_y - kHalfObject)};
  frame.polygon(object, {200, 40, 40});

  const Rgb jaw_colour = p.grasped ? Rgb{30, 160, 60} : Rgb{40, 40, 40};
  const double gap = p.closed ? 0.012 : 0.035;  // jaw distance from the arm's centre
  for (const double side : {-1.0, 1.0}) {
    const double x = p.arm_x + side * gap;
    frame.line(at(x, p.arm_y - 0.03), at(x, p.arm_y + 0.03), jaw_colour, 0.008);
  }
  frame.circle(at(p.arm_x, p.arm_y), 0.012, {40, 90, 200});
  frame.end_scene();
}

}  // namespace

bool Grasp2D::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error("Grasp2D-v0: call reset() before render()");
  draw({arm_x_, arm_y_, object_x_, object_y_, gripper_closed_, grasped_}, config_.success_threshold,
       frame);
  return true;
}

bool Grasp2D::render_observation(std::span<const float> obs, Frame& frame) const {
  if (obs.size() != 6)
    throw std::invalid_argument("Grasp2D-v0: an observation has 6 values, got " +
                                std::to_string(obs.size()));
  draw({obs[0], obs[1], obs[2], obs[3], obs[4] > 0.5f, obs[5] > 0.5f}, config_.success_threshold,
       frame);
  return true;
}

}  // namespace rlrun
