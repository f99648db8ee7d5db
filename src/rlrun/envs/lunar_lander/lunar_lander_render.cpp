// LunarLander's picture: LunarLander.render() in
// gymnasium/envs/box2d/lunar_lander.py (Gymnasium 1.0.0), same geometry and
// colours: a 600x400 scene in pixels (world units times SCALE = 30), y up;
// white ground, the sky above the terrain black, the hull and legs filled (128,
// 102, 230) and outlined (77, 77, 128), the helipad marked by two white poles
// 50 px high with yellow (204, 204, 0) flags. Gymnasium's exhaust particles are
// decoration that rlrun does not simulate (docs/box2d.md), so no flames are
// drawn.
#include <array>

#include "rlrun/envs/lunar_lander/lunar_lander.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

namespace {

constexpr double kScale = 30.0;                                     // SCALE
constexpr Rgb kBodyFill{128, 102, 230}, kBodyOutline{77, 77, 128};  // lander.color1, color2
constexpr Rgb kFlag{204, 204, 0};

template <size_t N>
void draw_body(const std::array<std::array<double, 2>, N>& outline, Frame& frame) {
  std::array<Point, N> path;
  for (size_t i = 0; i < N; ++i) path[i] = {outline[i][0] * kScale, outline[i][1] * kScale};
  frame.polygon(path, kBodyFill);
  std::array<Point, N + 1> closed;  // pygame.draw.aalines(..., closed=True)
  for (size_t i = 0; i <= N; ++i) closed[i] = path[i % N];
  frame.polyline(closed, kBodyOutline, 1.0);
}

}  // namespace

bool LunarLander::render(Frame& frame) const {
  const RenderSpec spec = render_spec();
  // pygame.draw.rect(surf, (255, 255, 255), ...): everything below the terrain
  // stays white.
  frame.begin_scene(spec.width, spec.height, {255, 255, 255});
  if (physics_) {
    // self.sky_polys: each chunk's quad from the terrain up to the top, black.
    for (int i = 0; i + 1 < kChunks; ++i) {
      const double top = spec.height;
      const Point sky[] = {{chunk_x_[i] * kScale, smooth_y_[i] * kScale},
                           {chunk_x_[i + 1] * kScale, smooth_y_[i + 1] * kScale},
                           {chunk_x_[i + 1] * kScale, top},
                           {chunk_x_[i] * kScale, top}};
      frame.polygon(sky, {0, 0, 0});
    }
    draw_body(hull_outline(), frame);
    for (int leg = 0; leg < 2; ++leg) draw_body(leg_outline(leg), frame);
    for (const double x_world : {helipad_x1_, helipad_x2_}) {
      const double x = x_world * kScale;
      const double flagy1 = helipad_y_ * kScale, flagy2 = flagy1 + 50;
      frame.line({x, flagy1}, {x, flagy2}, {255, 255, 255}, 1.0);
      const Point flag[] = {{x, flagy2}, {x, flagy2 - 10}, {x + 25, flagy2 - 5}};
      frame.polygon(flag, kFlag);
    }
  }
  frame.end_scene();
  return true;
}

}  // namespace rlrun
