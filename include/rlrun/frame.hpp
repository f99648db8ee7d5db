#pragma once
// An RGB frame to draw into: a Cairo image surface (antialiased 2D shapes and text, no display
// or GPU needed) with the few primitives Gymnasium's classic-control pictures use (pygame's
// gfxdraw polygon / circle / line). Envs draw in their own *scene* coordinates, Gymnasium's
// screen size with y pointing up (Gymnasium draws y-up and flips the surface at the end);
// begin_scene() maps that onto the frame at any size, keeping the aspect ratio. The pixels
// are Cairo's RGB24: one uint32 per pixel, 0x00RRGGBB in native byte order, which the video
// writer pipes to ffmpeg as it is and the 3D rasterizer writes directly.
// Part of the plugin API (header-only; a plugin that renders links Cairo, as rlrun does).
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
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

// --- implementation (header-only: plugin envs draw with the same code) ---

namespace frame_detail {

inline constexpr int kMaxSide = 16384;

inline void set_color(cairo_t* cr, Rgb c) {
  cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0);
}

inline void trace_path(cairo_t* cr, std::span<const Point> points) {
  cairo_new_path(cr);
  for (const Point& p : points) cairo_line_to(cr, p.x, p.y);
}

}  // namespace frame_detail

inline Frame::Frame(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > frame_detail::kMaxSide ||
      height > frame_detail::kMaxSide)
    throw std::invalid_argument("frame size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is not between 1 and " +
                                std::to_string(frame_detail::kMaxSide));
  surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
    const std::string reason = cairo_status_to_string(cairo_surface_status(surface_));
    release();
    throw std::runtime_error("cannot create a " + std::to_string(width) + "x" +
                             std::to_string(height) + " frame: " + reason);
  }
  cr_ = cairo_create(surface_);
  stride_pixels_ = cairo_image_surface_get_stride(surface_) / 4;
}

inline Frame::~Frame() { release(); }

inline Frame::Frame(Frame&& other) noexcept
    : width_(other.width_),
      height_(other.height_),
      stride_pixels_(other.stride_pixels_),
      scene_scale_(other.scene_scale_),
      surface_(std::exchange(other.surface_, nullptr)),
      cr_(std::exchange(other.cr_, nullptr)) {}

inline Frame& Frame::operator=(Frame&& other) noexcept {
  if (this != &other) {
    release();
    width_ = other.width_;
    height_ = other.height_;
    stride_pixels_ = other.stride_pixels_;
    scene_scale_ = other.scene_scale_;
    surface_ = std::exchange(other.surface_, nullptr);
    cr_ = std::exchange(other.cr_, nullptr);
  }
  return *this;
}

inline void Frame::release() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
  cr_ = nullptr;
  surface_ = nullptr;
}

inline void Frame::begin_scene(double scene_width, double scene_height, Rgb background, bool y_up) {
  cairo_identity_matrix(cr_);
  fill(background);
  const double scale = std::min(width_ / scene_width, height_ / scene_height);
  const double x0 = (width_ - scene_width * scale) / 2;
  const double y0 = (height_ - scene_height * scale) / 2;
  // Margins outside the scene stay background; drawing is clipped to the scene like pygame's
  // surface clips to its size.
  cairo_reset_clip(cr_);
  cairo_rectangle(cr_, x0, y0, scene_width * scale, scene_height * scale);
  cairo_clip(cr_);
  if (y_up) {
    // Scene y (up) -> pixel y (down): pygame.transform.flip(surf, False, True) maps a
    // scene row y to frame row H - y.
    cairo_translate(cr_, x0, y0 + scene_height * scale);
    cairo_scale(cr_, scale, -scale);
  } else {
    cairo_translate(cr_, x0, y0);
    cairo_scale(cr_, scale, scale);
  }
  scene_scale_ = scale;
}

inline void Frame::end_scene() {
  cairo_identity_matrix(cr_);
  cairo_reset_clip(cr_);
  scene_scale_ = 1.0;
}

inline void Frame::fill(Rgb color) {
  frame_detail::set_color(cr_, color);
  cairo_paint(cr_);
}

inline void Frame::polygon(std::span<const Point> points, Rgb color) {
  if (points.size() < 3) return;
  frame_detail::trace_path(cr_, points);
  cairo_close_path(cr_);
  frame_detail::set_color(cr_, color);
  cairo_fill(cr_);
}

inline void Frame::circle(Point centre, double radius, Rgb color) {
  cairo_new_path(cr_);
  cairo_arc(cr_, centre.x, centre.y, radius, 0, 2 * std::numbers::pi);
  frame_detail::set_color(cr_, color);
  cairo_fill(cr_);
}

inline void Frame::line(Point a, Point b, Rgb color, double width) {
  const Point points[] = {a, b};
  polyline(points, color, width);
}

inline void Frame::polyline(std::span<const Point> points, Rgb color, double width) {
  if (points.size() < 2) return;
  frame_detail::trace_path(cr_, points);
  frame_detail::set_color(cr_, color);
  cairo_set_line_width(cr_, width);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr_);
}

inline uint32_t* Frame::pixels() {
  cairo_surface_flush(surface_);
  return reinterpret_cast<uint32_t*>(cairo_image_surface_get_data(surface_));
}

inline const uint32_t* Frame::pixels() const {
  cairo_surface_flush(surface_);
  return reinterpret_cast<const uint32_t*>(cairo_image_surface_get_data(surface_));
}

inline void Frame::mark_dirty() { cairo_surface_mark_dirty(surface_); }

inline Rgb Frame::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the frame");
  const uint32_t p = pixels()[static_cast<size_t>(y) * stride_pixels_ + x];
  return {static_cast<uint8_t>(p >> 16), static_cast<uint8_t>(p >> 8), static_cast<uint8_t>(p)};
}

inline void Frame::to_rgb(std::vector<uint8_t>& out) const {
  out.resize(static_cast<size_t>(width_) * height_ * 3);
  const uint32_t* data = pixels();
  uint8_t* o = out.data();
  for (int y = 0; y < height_; ++y) {
    const uint32_t* row = data + static_cast<size_t>(y) * stride_pixels_;
    for (int x = 0; x < width_; ++x) {
      *o++ = static_cast<uint8_t>(row[x] >> 16);
      *o++ = static_cast<uint8_t>(row[x] >> 8);
      *o++ = static_cast<uint8_t>(row[x]);
    }
  }
}

inline void Frame::write_png(const std::string& path) const {
  cairo_surface_flush(surface_);
  const cairo_status_t status = cairo_surface_write_to_png(surface_, path.c_str());
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cannot write " + path + ": " + cairo_status_to_string(status));
}

}  // namespace rlrun
