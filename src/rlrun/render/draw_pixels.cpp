#include "rlrun/render/draw_pixels.hpp"

#include <algorithm>
#include <cstdint>

namespace rlrun {

void draw_pixels(std::span<const float> image, int height, int width, int channels, Frame& frame) {
  const auto level = [](float v) { return static_cast<uint32_t>(std::clamp(v, 0.0f, 255.0f)); };
  uint32_t* out = frame.pixels();
  for (int y = 0; y < frame.height(); ++y) {
    const int sy = std::min(height - 1, static_cast<int>(int64_t{y} * height / frame.height()));
    for (int x = 0; x < frame.width(); ++x) {
      const int sx = std::min(width - 1, static_cast<int>(int64_t{x} * width / frame.width()));
      const float* p = image.data() + (static_cast<size_t>(sy) * width + sx) * channels;
      const uint32_t r = level(p[0]);
      const uint32_t g = channels == 3 ? level(p[1]) : r, b = channels == 3 ? level(p[2]) : r;
      out[static_cast<size_t>(y) * frame.stride_pixels() + x] = r << 16 | g << 8 | b;
    }
  }
}

}  // namespace rlrun
