#pragma once
// The two OpenCV calls the image wrappers of Gymnasium 0.29, SB3 and rl-zoo make on uint8 frames,
// bit for bit as OpenCV 4.x computes them on x86-64 (modules/imgproc/src/color_rgb.simd.hpp and
// resize.cpp; checked against Debian's OpenCV 4.6 by tests/data/opencv/, made by
// scripts/tests/make_opencv_golden.py):
//  * cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY): ITU-R BT.601 luma in 15-bit fixed point,
//    (9798 r + 19235 g + 3735 b + 16384) >> 15 (0.299, 0.587, 0.114 times 2^15, rounded).
//    Gymnasium 0.29's GrayScaleObservation and SB3's WarpFrame use it; Gymnasium 1.0's
//    GrayscaleObservation uses float weights instead (grayscale_observation.hpp).
//  * cv2.resize(image, (width, height), interpolation=cv2.INTER_AREA) when no side grows: the
//    mean of each destination pixel's source area. An integer factor on both sides averages
//    whole blocks — (a + b + c + d + 2) >> 2 for 2x2 blocks of 1, 3 or 4 channels, else
//    round(sum * (1/area)) in float — and any other factor weighs the partly covered source
//    pixels by their covered fraction, accumulated in float in OpenCV's order and rounded half
//    to even.
// Pixels are floats holding 0-255 (rlrun's observations); each is first taken as OpenCV would
// see the uint8 array Gymnasium's Box holds (rounded, clamped to 0-255).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rlrun {

struct ImageSize {
  int height = 0, width = 0, channels = 1;  // channels-last, row 0 at the top
  int64_t values() const { return int64_t{height} * width * channels; }
};

// The uint8 value OpenCV reads for a float pixel of an rlrun observation.
uint8_t opencv_pixel(float value);

// cv2.COLOR_RGB2GRAY of one pixel.
uint8_t opencv_rgb_to_gray(uint8_t r, uint8_t g, uint8_t b);

// Why cv2.INTER_AREA from `from` to (height, width) cannot be computed here, or "" when it can:
// a side that grows (OpenCV then interpolates linearly, which rlrun does not implement), or more
// than 4 channels at a factor that is not an integer (OpenCV asserts cn <= 4 there).
std::string opencv_area_resize_refusal(const ImageSize& from, int height, int width);

// cv2.resize(src, (width, height), interpolation=cv2.INTER_AREA) of a channels-last uint8 image
// of size `from` into `dst` (height * width * from.channels values). Throws
// std::invalid_argument with opencv_area_resize_refusal's reason.
void opencv_area_resize(std::span<const uint8_t> src, const ImageSize& from, int height, int width,
                        std::span<uint8_t> dst);

}  // namespace rlrun
