#pragma once
// The byte a float pixel value stands for: rounded to nearest (ties to even, as lrint and
// numpy's rint), clamped to 0-255, NaN 0. A uint8 Box holds whole numbers, which this keeps
// exactly; the clamp keeps a value an env got wrong from wrapping around. Inline and
// branch-free, so a frame's conversion vectorises. Used where images become bytes: OpenCV's
// input (wrappers/opencv_image_ops.hpp) and the buffers' storage (observation_columns.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rlrun {

inline uint8_t pixel_byte(float value) {
  const float v = value > 0.f ? std::min(value, 255.f) : 0.f;
  return static_cast<uint8_t>(static_cast<int>(std::nearbyint(v)));
}

}  // namespace rlrun
