// CarRacing's picture: CarRacing._render, _render_road, _render_indicators and Car.draw in
// gymnasium/envs/box2d/car_racing.py and car_dynamics.py (Gymnasium 1.0.0), same geometry and
// colours. Gymnasium draws a 1000x800 window (y up, then flipped) following the car: rotated
// so the car points up, centred horizontally a quarter of the way up, zooming in over the
// first second; then the indicator bar and the reward over the bottom, and shrinks the window
// to 96x96 (state pixels, no skid marks) or 600x400 (video). rlrun draws the same shapes
// straight at the target size on a supersampled canvas (render/polygon_canvas.hpp), which is
// what the shrink averages. The reward digits are seven-segment glyphs, not pygame's font.
#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "rlrun/envs/car_racing/car_dynamics.hpp"
#include "rlrun/envs/car_racing/car_racing.hpp"
#include "rlrun/render/polygon_canvas.hpp"

namespace rlrun {

namespace {

using namespace car_racing;

constexpr double kWindowW = 1000, kWindowH = 800;  // WINDOW_W, WINDOW_H
constexpr double kZoom = 2.7;                      // ZOOM: camera zoom
constexpr Rgb kHullColor{204, 0, 0};               // hull.color (0.8, 0, 0)
constexpr Rgb kWheelColor{0, 0, 0};                // WHEEL_COLOR
constexpr Rgb kWheelWhite{77, 77, 77};             // WHEEL_WHITE: the rotating stripe
constexpr Rgb kMudColor{102, 102, 0};              // MUD_COLOR: skid marks on grass
constexpr int kVideoSupersample = 2;               // samples per video pixel and axis

Rgb truncated(const std::array<double, 3>& c, double add = 0) {
  const auto channel = [add](double v) {
    return static_cast<uint8_t>(std::clamp(std::floor(v + add), 0.0, 255.0));
  };
  return {channel(c[0]), channel(c[1]), channel(c[2])};
}

// World -> output pixels: Gymnasium's rotation, zoom and translation into the window, its
// vertical flip, and the window's scale onto the canvas.
struct View {
  double angle, zoom;
  Point trans;
  double sx, sy;
  Point operator()(double x, double y) const {
    const Point q = rotate({x, y}, angle);
    return {(q.x * zoom + trans.x) * sx, (kWindowH - (q.y * zoom + trans.y)) * sy};
  }
};

// True when a polygon's output bounding box meets the canvas (Gymnasium skips shapes off the
// window too; this only saves time).
template <size_t N>
bool visible(const std::array<Point, N>& p, const PolygonCanvas& canvas) {
  double x0 = p[0].x, x1 = p[0].x, y0 = p[0].y, y1 = p[0].y;
  for (const Point& q : p) {
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  return x1 >= 0 && y1 >= 0 && x0 <= canvas.width() && y0 <= canvas.height();
}

void draw_quad(const Quad& quad, const View& view, Rgb color, PolygonCanvas& canvas) {
  std::array<Point, 4> p;
  for (int k = 0; k < 4; ++k) p[k] = view(quad[k][0], quad[k][1]);
  if (visible(p, canvas)) canvas.polygon(p, color);
}

// Every fixture of a body, in the body's frame, placed by its transform.
void draw_body(const b2Body* body, const View& view, Rgb color, PolygonCanvas& canvas) {
  const b2Transform& t = body->GetTransform();
  for (const b2Fixture* f = body->GetFixtureList(); f; f = f->GetNext()) {
    const auto* shape = static_cast<const b2PolygonShape*>(f->GetShape());
    std::array<Point, b2_maxPolygonVertices> p;
    for (int k = 0; k < shape->m_count; ++k) {
      const b2Vec2 v = b2Mul(t, shape->m_vertices[k]);
      p[k] = view(v.x, v.y);
    }
    canvas.polygon(std::span<const Point>(p.data(), static_cast<size_t>(shape->m_count)), color);
  }
}

// The grey stripe that shows a wheel turning (Car.draw): the part of the wheel between phase
// and phase + 1.2 rad as seen from the side, hidden while both angles face away.
void draw_wheel_stripe(const b2Body* body, double phase, const View& view, PolygonCanvas& canvas) {
  const double a1 = phase, a2 = phase + 1.2;
  const double s1 = std::sin(a1), s2 = std::sin(a2);
  double c1 = std::cos(a1), c2 = std::cos(a2);
  if (s1 > 0 && s2 > 0) return;
  if (s1 > 0) c1 = sign(c1);
  if (s2 > 0) c2 = sign(c2);
  const double w = kWheelW * kSize, r = kWheelR * kSize;
  const double local[4][2] = {{-w, r * c1}, {+w, r * c1}, {+w, r * c2}, {-w, r * c2}};
  const b2Transform& t = body->GetTransform();
  std::array<Point, 4> p;
  for (int k = 0; k < 4; ++k) {
    const b2Vec2 v =
        b2Mul(t, b2Vec2(static_cast<float>(local[k][0]), static_cast<float>(local[k][1])));
    p[k] = view(v.x, v.y);
  }
  canvas.polygon(p, kWheelWhite);
}

// Seven-segment glyphs for the reward counter ("%04i"), in window pixels: a cell of 20 x 30
// with 5-pixel strokes, about the digits of pygame's 42-point default font.
void draw_counter(double value, double sx, double sy, PolygonCanvas& canvas) {
  char text[32];
  std::snprintf(text, sizeof text, "%04d",
                static_cast<int>(std::trunc(std::clamp(value, -1e9, 1e9))));
  // Segments a..g as rectangles (x0, y0, x1, y1) in the 20 x 30 cell.
  static constexpr double kSegments[7][4] = {{0, 0, 20, 5},      {15, 0, 20, 15}, {15, 15, 20, 30},
                                             {0, 25, 20, 30},    {0, 15, 5, 30},  {0, 0, 5, 15},
                                             {0, 12.5, 20, 17.5}};
  // Which segments (bit 0 = a .. bit 6 = g) each digit lights.
  static constexpr uint8_t kDigits[10] = {0x3f, 0x06, 0x5b, 0x4f, 0x66,
                                          0x6d, 0x7d, 0x07, 0x7f, 0x6f};
  const double advance = 23.4;
  const size_t n = std::char_traits<char>::length(text);
  const double left = 60 - advance * static_cast<double>(n) / 2 + 1.7;
  const double top = kWindowH - kWindowH * 2.5 / 40.0 - 15;  // text_rect.center's y
  for (size_t i = 0; i < n; ++i) {
    const uint8_t lit =
        text[i] == '-' ? 0x40 : (text[i] >= '0' && text[i] <= '9' ? kDigits[text[i] - '0'] : 0);
    const double x = left + advance * static_cast<double>(i);
    for (int s = 0; s < 7; ++s)
      if (lit & (1u << s))
        canvas.rect((x + kSegments[s][0]) * sx, (top + kSegments[s][1]) * sy,
                    (x + kSegments[s][2]) * sx, (top + kSegments[s][3]) * sy, {255, 255, 255});
  }
}

// CarRacing._render_indicators, in window pixels after the flip: a black bar over the bottom
// 5/40 with the true speed (white), the four wheels' spin (blue), the steering (green) and
// the yaw rate (red) as bars; each drawn only when its value exceeds 1e-4.
void draw_indicators(const CarState& car, double sx, double sy, PolygonCanvas& canvas) {
  const double W = kWindowW, H = kWindowH, s = W / 40.0, h = H / 40.0;
  canvas.rect(0, (H - 5 * h) * sy, W * sx, H * sy, {0, 0, 0});
  const auto vertical = [&](double place, double val, Rgb color) {
    canvas.rect(place * s * sx, (H - (h + h * val)) * sy, (place + 1) * s * sx, (H - h) * sy,
                color);
  };
  const auto horizontal = [&](double place, double value, Rgb color) {
    canvas.rect(place * s * sx, (H - 4 * h) * sy, (place + value) * s * sx, (H - 2 * h) * sy,
                color);
  };
  const double true_speed = std::hypot(car.hull.linear_velocity[0], car.hull.linear_velocity[1]);
  if (true_speed > 1e-4) vertical(5, 0.02 * true_speed, {255, 255, 255});
  // render_if_min tests the raw value, then draws the scaled bar.
  const auto wheel = [&](int i, double place, Rgb color) {
    if (std::abs(car.wheels[i].omega) > 1e-4) vertical(place, 0.01 * car.wheels[i].omega, color);
  };
  wheel(0, 7, {0, 0, 255});
  wheel(1, 8, {0, 0, 255});
  wheel(2, 9, {51, 0, 255});
  wheel(3, 10, {51, 0, 255});
  if (std::abs(car.wheels[0].joint_angle) > 1e-4)
    horizontal(20, -10.0 * car.wheels[0].joint_angle, {0, 255, 0});
  if (std::abs(car.hull.angular_velocity) > 1e-4)
    horizontal(30, -0.8 * car.hull.angular_velocity, {255, 0, 0});
}

}  // namespace

void CarRacing::draw_scene(PolygonCanvas& canvas, bool skid_marks) const {
  const Car& car = car_model();
  const b2Body* hull = car.hull();
  const double sx = canvas.width() / kWindowW, sy = canvas.height() / kWindowH;
  // "Animating first second zoom."
  const double zoom = 0.1 * kScale * std::max(1 - t_, 0.0) + kZoom * kScale * std::min(t_, 1.0);
  const double angle = -hull->GetAngle();
  const Point scroll =
      rotate({-hull->GetPosition().x * zoom, -hull->GetPosition().y * zoom}, angle);
  const View view{angle, zoom, {kWindowW / 2 + scroll.x, kWindowH / 4 + scroll.y}, sx, sy};

  canvas.clear({0, 0, 0});
  // _render_road: the playfield, the lighter grass squares of a 2x2 checker, the tiles (each
  // followed by its kerb).
  const double b = kPlayfield;
  draw_quad({{{b, b}, {b, -b}, {-b, -b}, {-b, b}}}, view, truncated(colors_.bg), canvas);
  const Rgb grass = truncated(colors_.grass);
  for (int x = -20; x < 20; x += 2)
    for (int y = -20; y < 20; y += 2) {
      const double gx = kGrassDim * x, gy = kGrassDim * y;
      draw_quad({{{gx + kGrassDim, gy},
                  {gx, gy},
                  {gx, gy + kGrassDim},
                  {gx + kGrassDim, gy + kGrassDim}}},
                view, grass, canvas);
    }
  size_t kerb = 0;
  for (size_t i = 0; i < road_.tiles.size(); ++i) {
    // road_color + 0.01 * (i % 3) * 255, until something touches the tile.
    const double shade = tile_touched_[i] ? 0.0 : 0.01 * static_cast<double>(i % 3) * 255;
    draw_quad(road_.tiles[i], view, truncated(colors_.road, shade), canvas);
    for (; kerb < road_.kerbs.size() && road_.kerbs[kerb].tile == static_cast<int>(i); ++kerb)
      draw_quad(road_.kerbs[kerb].quad, view,
                road_.kerbs[kerb].red ? Rgb{255, 0, 0} : Rgb{255, 255, 255}, canvas);
  }
  if (skid_marks) {
    for (const auto& mark : car.skid_marks()) {
      std::vector<Point> p;
      for (const auto& [x, y] : mark->points) p.push_back(view(x, y));
      canvas.polyline(p, 2 * (sx + sy) / 2, mark->grass ? kMudColor : kWheelColor);
    }
  }
  for (int w = 0; w < 4; ++w) {  // drawlist = wheels + [hull]
    draw_body(car.wheel_body(w), view, kWheelColor, canvas);
    draw_wheel_stripe(car.wheel_body(w), car.wheel_phase(w), view, canvas);
  }
  draw_body(hull, view, kHullColor, canvas);
  draw_indicators(car.state(), sx, sy, canvas);
  draw_counter(reward_, sx, sy, canvas);
}

bool CarRacing::render(Frame& frame) const {
  if (!physics_) {
    frame.fill({0, 0, 0});
    return true;
  }
  PolygonCanvas canvas(frame.width(), frame.height(), kVideoSupersample);
  draw_scene(canvas, true);
  canvas.resolve(frame);
  return true;
}

}  // namespace rlrun
