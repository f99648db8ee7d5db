#include "rlrun/render/polygon_canvas.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {
constexpr int kMaxSamplesPerSide = 16384;
// resolve()'s channel sums hold up to 16 x 16 samples a pixel.
constexpr int kMaxSupersample = 16;
// resolve()'s channel fields (below).
constexpr uint32_t kRedBlue = 0x00ff00ffu, kGreen = 0xffu, kField = 0xffffu;

uint32_t pack(Rgb c) { return (uint32_t{c.r} << 16) | (uint32_t{c.g} << 8) | uint32_t{c.b}; }
}  // namespace

PolygonCanvas::PolygonCanvas(int width, int height, int supersample)
    : width_(width), height_(height), ss_(supersample) {
  if (width <= 0 || height <= 0 || supersample <= 0 || supersample > kMaxSupersample ||
      int64_t{width} * supersample > kMaxSamplesPerSide ||
      int64_t{height} * supersample > kMaxSamplesPerSide)
    throw std::invalid_argument("PolygonCanvas: bad size " + std::to_string(width) + "x" +
                                std::to_string(height) + " x" + std::to_string(supersample));
  sample_width_ = width * supersample;
  sample_height_ = height * supersample;
  samples_.assign(static_cast<size_t>(sample_width_) * sample_height_, 0);
}

void PolygonCanvas::clear(Rgb color) { std::fill(samples_.begin(), samples_.end(), pack(color)); }

void PolygonCanvas::polygon(std::span<const Point> points, Rgb color) {
  if (points.size() < 3) return;
  const uint32_t value = pack(color);
  // In sample units: sample (i, j) sits at (i + 0.5, j + 0.5).
  double y_min = points[0].y, y_max = points[0].y;
  for (const Point& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    y_min = std::min(y_min, p.y);
    y_max = std::max(y_max, p.y);
  }
  if (y_max < 0.0 || y_min > height_) return;
  const auto sample_index = [](double v, int limit) {
    return static_cast<int>(std::ceil(std::clamp(v, -1.0, static_cast<double>(limit))));
  };
  const int row_begin = std::max(0, sample_index(y_min * ss_ - 0.5, sample_height_));
  const int row_end = sample_index(y_max * ss_ - 0.5, sample_height_);
  const size_t n = points.size();
  for (int row = row_begin; row < row_end; ++row) {
    const double y = (row + 0.5) / ss_;
    crossings_.clear();
    for (size_t k = 0; k < n; ++k) {
      const Point& a = points[k];
      const Point& b = points[(k + 1) % n];
      // Half-open in y so a vertex on the row counts once.
      if ((a.y <= y) != (b.y <= y))
        crossings_.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(crossings_.begin(), crossings_.end());
    uint32_t* line = samples_.data() + static_cast<size_t>(row) * sample_width_;
    for (size_t k = 0; k + 1 < crossings_.size(); k += 2) {
      const int c0 = std::max(0, sample_index(crossings_[k] * ss_ - 0.5, sample_width_));
      const int c1 = sample_index(crossings_[k + 1] * ss_ - 0.5, sample_width_);
      if (c1 > c0) std::fill(line + c0, line + c1, value);
    }
  }
}

void PolygonCanvas::rect(double x0, double y0, double x1, double y1, Rgb color) {
  const Point corners[] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  polygon(corners, color);
}

void PolygonCanvas::polyline(std::span<const Point> points, double width, Rgb color) {
  const double half = width / 2;
  for (size_t k = 0; k + 1 < points.size(); ++k) {
    const Point a = points[k], b = points[k + 1];
    const double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
    if (!(length > 0)) continue;
    const double nx = -dy / length * half, ny = dx / length * half;
    const Point quad[] = {
        {a.x + nx, a.y + ny}, {b.x + nx, b.y + ny}, {b.x - nx, b.y - ny}, {a.x - nx, a.y - ny}};
    polygon(quad, color);
  }
}

// Channel sums two at a time in 16-bit fields of a 32-bit word: red and blue are bits 16-23 and
// 0-7 of a sample already (0x00RRGGBB), green alone after a shift, and up to 16 x 16 samples
// a pixel (256 x 255 < 2^16) never carry into the next field. Sums go down the sample columns
// first (contiguous, so the compiler vectorizes them), then across each pixel's columns.
// Resolving the 96x96 CarRacing observation (16 samples a pixel) with three shifts and masks
// per channel and sample took 13 % of a whole PPO CarRacing run.
void PolygonCanvas::resolve(std::span<uint8_t> rgb) const {
  if (rgb.size() != static_cast<size_t>(width_) * height_ * 3)
    throw std::invalid_argument("PolygonCanvas::resolve: wrong buffer size");
  const uint32_t count = static_cast<uint32_t>(ss_ * ss_);
  const uint32_t round = count / 2;
  const int shift = std::has_single_bit(count) ? std::countr_zero(count) : -1;
  const size_t columns = static_cast<size_t>(sample_width_);
  // Fresh vectors per frame (3 KiB, small beside the 590 KiB of samples read): the compiler
  // then knows they do not alias the samples; member scratch vectors were not faster here.
  std::vector<uint32_t> red_blue(columns), green(columns);
  for (int y = 0; y < height_; ++y) {
    std::fill(red_blue.begin(), red_blue.end(), 0);
    std::fill(green.begin(), green.end(), 0);
    for (int sy = 0; sy < ss_; ++sy) {
      const uint32_t* s = samples_.data() + static_cast<size_t>(y * ss_ + sy) * columns;
      for (size_t i = 0; i < columns; ++i) {
        red_blue[i] += s[i] & kRedBlue;
        green[i] += (s[i] >> 8) & kGreen;
      }
    }
    uint8_t* out = rgb.data() + static_cast<size_t>(y) * width_ * 3;
    // Rounded means: a shift when the sample count is a power of two (4x4 here), since
    // divisions cost as much as all the additions.
    const auto write = [&](auto mean) {
      for (size_t x = 0; x < static_cast<size_t>(width_); ++x, out += 3) {
        uint32_t rb = 0, g = 0;
        for (size_t i = x * static_cast<size_t>(ss_); i < (x + 1) * static_cast<size_t>(ss_); ++i) {
          rb += red_blue[i];
          g += green[i];
        }
        out[0] = static_cast<uint8_t>(mean((rb >> 16) + round));
        out[1] = static_cast<uint8_t>(mean(g + round));
        out[2] = static_cast<uint8_t>(mean((rb & kField) + round));
      }
    };
    if (shift >= 0)
      write([shift](uint32_t v) { return v >> shift; });
    else
      write([count](uint32_t v) { return v / count; });
  }
}

void PolygonCanvas::resolve(Frame& frame) const {
  if (frame.width() != width_ || frame.height() != height_)
    throw std::invalid_argument("PolygonCanvas::resolve: the frame's size differs");
  std::vector<uint8_t> rgb(static_cast<size_t>(width_) * height_ * 3);
  resolve(rgb);
  uint32_t* pixels = frame.pixels();
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const uint8_t* p = rgb.data() + (static_cast<size_t>(y) * width_ + x) * 3;
      pixels[static_cast<size_t>(y) * frame.stride_pixels() + x] = pack({p[0], p[1], p[2]});
    }
  frame.mark_dirty();
}

}  // namespace rlrun
