// BipedalWalker's picture, drawn as Gymnasium 1.0's BipedalWalker.render draws it
// (gymnasium/envs/box2d/bipedal_walker.py): a 600x400 window that follows the hull (its left
// edge VIEWPORT_W / SCALE / 5 behind it), pale sky, clouds moving at half speed, green ground
// under a two-tone grass line, white obstacles, the legs in two shades of purple and the hull,
// one lidar ray at a time sweeping in red, and the start flag.
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "rlrun/envs/bipedal_walker/bipedal_walker.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

using namespace walker;

namespace {

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kSky{215, 215, 255};
constexpr Rgb kCloud{255, 255, 255};
constexpr Rgb kGround{102, 153, 76};
constexpr Rgb kObstacleFill{255, 255, 255}, kObstacleLine{153, 153, 153};
constexpr Rgb kHullFill{127, 51, 229}, kHullLine{76, 76, 127};
constexpr Rgb kLidar{255, 0, 0};
constexpr Rgb kFlag{230, 51, 0};

// Leg colours of leg side i = -1 (legs 0, 1) and +1 (legs 2, 3): (153 - 25 i, 76 - 25 i,
// 127 - 25 i) filled, (102 - 25 i, 51 - 25 i, 76 - 25 i) outlined.
Rgb leg_fill(int i) {
  return {static_cast<uint8_t>(153 - 25 * i), static_cast<uint8_t>(76 - 25 * i),
          static_cast<uint8_t>(127 - 25 * i)};
}
Rgb leg_line(int i) {
  return {static_cast<uint8_t>(102 - 25 * i), static_cast<uint8_t>(51 - 25 * i),
          static_cast<uint8_t>(76 - 25 * i)};
}

// Filled and outlined as Gymnasium draws a polygon fixture (polygon + aapolygon in color1,
// then a one-pixel outline in color2).
void draw_outlined(Frame& frame, std::span<const Point> path, Rgb fill, Rgb line) {
  frame.polygon(path, fill);
  std::vector<Point> closed(path.begin(), path.end());
  closed.push_back(path[0]);
  frame.polyline(closed, line, 1.0);
}

// The window onto the world: it starts at world x `scroll`; Gymnasium draws on a surface
// VIEWPORT_W + max(0, scroll) * SCALE wide and keeps its last VIEWPORT_W columns, so pixels
// are shifted left by max(0, scroll) * SCALE.
struct View {
  double scroll;
  double left = std::max(0.0, scroll) * kScale;
  Point px(double wx, double wy) const { return Point{wx * kScale - left, wy * kScale}; }
};

// Sky, the clouds (moving at half the scroll's speed) and the ground under the visible edges.
void draw_background(Frame& frame, const View& view, const Terrain& terrain) {
  const double scroll = view.scroll;
  const Point sky[] = {view.px(scroll, 0), view.px(scroll + kViewportW / kScale, 0),
                       view.px(scroll + kViewportW / kScale, kViewportH / kScale),
                       view.px(scroll, kViewportH / kScale)};
  frame.polygon(sky, kSky);

  std::vector<Point> path;
  for (const Cloud& cloud : terrain.clouds) {
    if (cloud.x2 < scroll / 2 || cloud.x1 > scroll / 2 + kViewportW / kScale) continue;
    path.clear();
    for (const Vec2d& p : cloud.corners) path.push_back(view.px(p.x + scroll / 2, p.y));
    frame.polygon(path, kCloud);
  }
  // terrain_poly: Gymnasium fills one quad under each visible edge, down to y = 0. Drawn as
  // one polygon here, the same area, so that antialiasing leaves no seams between the quads.
  path.clear();
  double ground_x0 = 0, ground_x1 = 0;
  for (size_t i = 0; i + 1 < terrain.x.size(); ++i) {
    if (terrain.x[i + 1] < scroll || terrain.x[i] > scroll + kViewportW / kScale) continue;
    if (path.empty()) {
      ground_x0 = terrain.x[i];
      path.push_back(view.px(terrain.x[i], terrain.y[i]));
    }
    path.push_back(view.px(terrain.x[i + 1], terrain.y[i + 1]));
    ground_x1 = terrain.x[i + 1];
  }
  path.push_back(view.px(ground_x1, 0));
  path.push_back(view.px(ground_x0, 0));
  if (path.size() > 2) frame.polygon(path, kGround);
}

// Gymnasium's drawlist's terrain part, reversed: grass edges last to first, then the obstacles.
void draw_terrain_edges(Frame& frame, const View& view, const Terrain& terrain) {
  for (size_t i = terrain.x.size() - 1; i-- > 0;) {
    const Rgb grass{76, static_cast<uint8_t>(i % 2 == 0 ? 255 : 204), 76};
    frame.line(view.px(terrain.x[i], terrain.y[i]), view.px(terrain.x[i + 1], terrain.y[i + 1]),
               grass);
  }
  std::vector<Point> path;
  for (auto it = terrain.obstacles.rbegin(); it != terrain.obstacles.rend(); ++it) {
    path.clear();
    for (const Vec2d& p : it->corners) path.push_back(view.px(p.x, p.y));
    draw_outlined(frame, path, kObstacleFill, kObstacleLine);
  }
}

// Every polygon fixture of the body, where the body is now.
void draw_body(Frame& frame, const View& view, const b2Body* body, Rgb fill, Rgb line) {
  const b2Transform& xf = body->GetTransform();
  std::vector<Point> path;
  for (const b2Fixture* f = body->GetFixtureList(); f; f = f->GetNext()) {
    const auto* shape = static_cast<const b2PolygonShape*>(f->GetShape());
    path.clear();
    for (int k = 0; k < shape->m_count; ++k) {
      const b2Vec2 v = b2Mul(xf, shape->m_vertices[k]);
      path.push_back(view.px(v.x, v.y));
    }
    draw_outlined(frame, path, fill, line);
  }
}

// The start flag, in pixels: a pole 50 high at x = 3 TERRAIN_STEP and a pennant.
void draw_flag(Frame& frame, const View& view) {
  const double flag_x = kTerrainStep * 3 * kScale - view.left;
  const double flag_y1 = kTerrainHeight * kScale, flag_y2 = flag_y1 + 50;
  frame.line({flag_x, flag_y1}, {flag_x, flag_y2}, kBlack);
  const Point pennant[] = {{flag_x, flag_y2}, {flag_x, flag_y2 - 10}, {flag_x + 25, flag_y2 - 5}};
  draw_outlined(frame, pennant, kFlag, kBlack);
}

}  // namespace

bool BipedalWalker::render(Frame& frame) const {
  if (!hull_) throw std::logic_error(id() + ": call reset() before render()");
  const View view{hull_->GetPosition().x - kViewportW / kScale / 5};
  frame.begin_scene(kViewportW, kViewportH, kBlack);
  draw_background(frame, view, terrain_);

  // self.lidar_render counts renders since the reset (1 at the reset's picture) modulo 100;
  // the first 20 show rays 0..9 and back.
  const int sweep = (episode_steps_ + 1) % 100;
  if (sweep < 2 * kLidarRays) {
    const int ray = sweep < kLidarRays ? sweep : 2 * kLidarRays - 1 - sweep;
    const auto [p1, p2] = lidar_ray(ray);
    frame.line(view.px(p1.x, p1.y), view.px(p2.x, p2.y), kLidar, 1.0);
  }

  // drawlist = reversed terrain, legs, hull.
  draw_terrain_edges(frame, view, terrain_);
  for (size_t k = 0; k < legs_.size(); ++k) {
    const int side = k < 2 ? -1 : +1;
    draw_body(frame, view, legs_[k], leg_fill(side), leg_line(side));
  }
  draw_body(frame, view, hull_, kHullFill, kHullLine);
  draw_flag(frame, view);
  frame.end_scene();
  return true;
}

}  // namespace rlrun
