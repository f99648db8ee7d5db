#include "rlrun/render/yuv420.hpp"

#include <cstddef>

namespace rlrun {

namespace {

inline int red(uint32_t p) { return static_cast<int>((p >> 16) & 0xff); }
inline int green(uint32_t p) { return static_cast<int>((p >> 8) & 0xff); }
inline int blue(uint32_t p) { return static_cast<int>(p & 0xff); }

// Y = 16 + (66 R + 129 G + 25 B) / 256, rounded.
inline uint8_t luma(uint32_t p) {
  return static_cast<uint8_t>(((66 * red(p) + 129 * green(p) + 25 * blue(p) + 128) >> 8) + 16);
}

}  // namespace

void rgb24_to_yuv420p(const uint32_t* pixels, int stride_pixels, int width, int height,
                      uint8_t* out) {
  const size_t plane = static_cast<size_t>(width) * height;
  uint8_t* y_plane = out;
  uint8_t* u_plane = out + plane;
  uint8_t* v_plane = u_plane + plane / 4;
  for (int y = 0; y < height; ++y) {
    const uint32_t* row = pixels + static_cast<size_t>(y) * stride_pixels;
    uint8_t* y_out = y_plane + static_cast<size_t>(y) * width;
    for (int x = 0; x < width; ++x) y_out[x] = luma(row[x]);
  }
  const int half_width = width / 2;
  for (int y = 0; y < height / 2; ++y) {
    const uint32_t* top = pixels + static_cast<size_t>(2 * y) * stride_pixels;
    const uint32_t* bottom = top + stride_pixels;
    uint8_t* u_out = u_plane + static_cast<size_t>(y) * half_width;
    uint8_t* v_out = v_plane + static_cast<size_t>(y) * half_width;
    for (int x = 0; x < half_width; ++x) {
      const uint32_t a = top[2 * x], b = top[2 * x + 1], c = bottom[2 * x], d = bottom[2 * x + 1];
      const int r = red(a) + red(b) + red(c) + red(d);
      const int g = green(a) + green(b) + green(c) + green(d);
      const int bl = blue(a) + blue(b) + blue(c) + blue(d);
      // Sums of four pixels: divide by 4 * 256 = 1024 (>> 10), rounding with +512.
      // The +128 offset is added after the shift: right-shifting a negative sum floors.
      u_out[x] = static_cast<uint8_t>(((-38 * r - 74 * g + 112 * bl + 512) >> 10) + 128);
      v_out[x] = static_cast<uint8_t>(((112 * r - 94 * g - 18 * bl + 512) >> 10) + 128);
    }
  }
}

}  // namespace rlrun
