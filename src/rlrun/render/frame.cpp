#include "rlrun/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace rlrun {

namespace {

constexpr int kMaxSide = 16384;

void set_color(cairo_t* cr, Rgb c) {
  cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0);
}

void trace_path(cairo_t* cr, std::span<const Point> points) {
  cairo_new_path(cr);
  for (const Point& p : points) cairo_line_to(cr, p.x, p.y);
}

}  // namespace

Frame::Frame(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide)
    throw std::invalid_argument("frame size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is not between 1 and " +
                                std::to_string(kMaxSide));
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

Frame::~Frame() { release(); }

Frame::Frame(Frame&& other) noexcept
    : width_(other.width_),
      height_(other.height_),
      stride_pixels_(other.stride_pixels_),
      scene_scale_(other.scene_scale_),
      surface_(std::exchange(other.surface_, nullptr)),
      cr_(std::exchange(other.cr_, nullptr)) {}

Frame& Frame::operator=(Frame&& other) noexcept {
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

void Frame::release() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
  cr_ = nullptr;
  surface_ = nullptr;
}

void Frame::begin_scene(double scene_width, double scene_height, Rgb background, bool y_up) {
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

void Frame::end_scene() {
  cairo_identity_matrix(cr_);
  cairo_reset_clip(cr_);
  scene_scale_ = 1.0;
}

void Frame::fill(Rgb color) {
  set_color(cr_, color);
  cairo_paint(cr_);
}

void Frame::polygon(std::span<const Point> points, Rgb color) {
  if (points.size() < 3) return;
  trace_path(cr_, points);
  cairo_close_path(cr_);
  set_color(cr_, color);
  cairo_fill(cr_);
}

void Frame::circle(Point centre, double radius, Rgb color) {
  cairo_new_path(cr_);
  cairo_arc(cr_, centre.x, centre.y, radius, 0, 2 * std::numbers::pi);
  set_color(cr_, color);
  cairo_fill(cr_);
}

void Frame::line(Point a, Point b, Rgb color, double width) {
  const Point points[] = {a, b};
  polyline(points, color, width);
}

void Frame::polyline(std::span<const Point> points, Rgb color, double width) {
  if (points.size() < 2) return;
  trace_path(cr_, points);
  set_color(cr_, color);
  cairo_set_line_width(cr_, width);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr_);
}

uint32_t* Frame::pixels() {
  cairo_surface_flush(surface_);
  return reinterpret_cast<uint32_t*>(cairo_image_surface_get_data(surface_));
}

const uint32_t* Frame::pixels() const {
  cairo_surface_flush(surface_);
  return reinterpret_cast<const uint32_t*>(cairo_image_surface_get_data(surface_));
}

void Frame::mark_dirty() { cairo_surface_mark_dirty(surface_); }

Rgb Frame::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the frame");
  const uint32_t p = pixels()[static_cast<size_t>(y) * stride_pixels_ + x];
  return {static_cast<uint8_t>(p >> 16), static_cast<uint8_t>(p >> 8), static_cast<uint8_t>(p)};
}

void Frame::to_rgb(std::vector<uint8_t>& out) const {
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

void Frame::write_png(const std::string& path) const {
  cairo_surface_flush(surface_);
  const cairo_status_t status = cairo_surface_write_to_png(surface_, path.c_str());
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cannot write " + path + ": " + cairo_status_to_string(status));
}

}  // namespace rlrun
