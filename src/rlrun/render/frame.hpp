#pragma once
// An RGB frame to draw into: a Cairo image surface (antialiased 2D shapes and text, no display
// or GPU needed) with the few primitives Gymnasium's classic-control pictures use (pygame's
// gfxdraw polygon / circle / line). Envs draw in their own *scene* coordinates, Gymnasium's
// screen size with y pointing up (Gymnasium draws y-up and flips the surface at the end);
// begin_scene() maps that onto the frame at any size, keeping the aspect ratio. The pixels
// are Cairo's RGB24: one uint32 per pixel, 0x00RRGGBB in native byte order, which the video
// writer pipes to ffmpeg as it is and the 3D rasterizer writes directly.
#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rlrun {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

struct Point {
  double x = 0, y = 0;
};

// `p` rotated counter-clockwise (in y-up coordinates) about the origin, as pygame's
// Vector2.rotate_rad, which Gymnasium's drawing code uses for every rotated shape.
inline Point rotate(Point p, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  return {p.x * c - p.y * s, p.x * s + p.y * c};
}
inline Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }

class Frame {
 public:
  // Throws std::invalid_argument unless 0 < width, height <= 16384.
  Frame(int width, int height);
  ~Frame();
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;
  Frame(Frame&& other) noexcept;
  Frame& operator=(Frame&& other) noexcept;

  int width() const { return width_; }
  int height() const { return height_; }

  // Fills the whole frame with `background`, then maps the scene rectangle [0, scene_width] x
  // [0, scene_height] onto the frame, scaled uniformly and centred (letterboxed: the
  // margins keep the background colour). With y_up the scene's y axis points up, as in
  // Gymnasium's drawing code before its final pygame.transform.flip.
  void begin_scene(double scene_width, double scene_height, Rgb background, bool y_up = true);
  // Back to pixel coordinates (origin top-left, y down), e.g. for overlays.
  void end_scene();
  // Pixels per scene unit of the current scene (1 outside a scene).
  double scene_scale() const { return scene_scale_; }

  // Drawing in the current coordinates. Polygons and circles are filled and antialiased
  // (gfxdraw.aapolygon + filled_polygon); line widths are in current units.
  void fill(Rgb color);
  void polygon(std::span<const Point> points, Rgb color);
  void circle(Point centre, double radius, Rgb color);
  void line(Point a, Point b, Rgb color, double width = 1.0);
  void polyline(std::span<const Point> points, Rgb color, double width = 1.0);

  // For anything else (text, arcs, gradients): the Cairo context, in the current coordinates.
  cairo_t* cairo() { return cr_; }

  // Pixel access. Call pixels() before writing directly (it flushes Cairo's pending drawing)
  // and mark_dirty() afterwards (so Cairo re-reads them). Rows are stride_pixels() apart.
  uint32_t* pixels();
  const uint32_t* pixels() const;
  int stride_pixels() const { return stride_pixels_; }
  void mark_dirty();
  Rgb pixel(int x, int y) const;

  // Tightly packed RGB24 bytes (row-major, top row first), e.g. for tests or other encoders.
  void to_rgb(std::vector<uint8_t>& out) const;
  // Throws std::runtime_error naming the file when it cannot be written.
  void write_png(const std::string& path) const;

 private:
  void release();
  int width_ = 0, height_ = 0, stride_pixels_ = 0;
  double scene_scale_ = 1.0;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

}  // namespace rlrun
