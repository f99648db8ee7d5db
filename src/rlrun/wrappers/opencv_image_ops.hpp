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

#include "rlrun/core/pixel_byte.hpp"

namespace rlrun {

struct ImageSize {
  int height = 0, width = 0, channels = 1;  // channels-last, row 0 at the top
  int64_t values() const { return int64_t{height} * width * channels; }
};

// The uint8 value OpenCV reads for a float pixel of an rlrun observation (core/pixel_byte.hpp;
// inline so a frame's conversion vectorises: it was 15 % of a pixel pipeline's step as a call).
inline uint8_t opencv_pixel(float value) { return pixel_byte(value); }

// cv2.COLOR_RGB2GRAY of one pixel.
uint8_t opencv_rgb_to_gray(uint8_t r, uint8_t g, uint8_t b);

// Why cv2.INTER_AREA from `from` to (height, width) cannot be computed here, or "" when it can:
// a side that grows (OpenCV then interpolates linearly, which rlrun does not implement), or more
// than 4 channels at a factor that is not an integer (OpenCV asserts cn <= 4 there).
std::string opencv_area_resize_refusal(const ImageSize& from, int height, int width);

// cv2.resize(src, (width, height), interpolation=cv2.INTER_AREA) of channels-last uint8 images
// of size `from`, with OpenCV's path and weight tables chosen once (a wrapper resizes every
// frame; no allocation per image).
class OpencvAreaResize {
 public:
  OpencvAreaResize() = default;
  // Throws std::invalid_argument with opencv_area_resize_refusal's reason.
  OpencvAreaResize(const ImageSize& from, int height, int width);

  // `src` (from.values() bytes) into `dst` (height * width * from.channels bytes). Throws
  // std::invalid_argument for other sizes.
  void operator()(std::span<const uint8_t> src, std::span<uint8_t> dst);

 private:
  // One destination index's share of a source index (OpenCV's DecimateAlpha).
  struct AreaWeight {
    int destination;  // times channels for columns
    int source;       // times channels for columns
    float alpha;
  };
  static std::vector<AreaWeight> area_weights(int source_size, int destination_size, int channels,
                                              double scale);
  void halve(std::span<const uint8_t> src, std::span<uint8_t> dst) const;
  void average_blocks(std::span<const uint8_t> src, std::span<uint8_t> dst) const;
  void weighted_area(std::span<const uint8_t> src, std::span<uint8_t> dst);

  enum class Path { kCopy, kHalve, kBlocks, kWeighted };
  ImageSize from_;
  int height_ = 0, width_ = 0;
  Path path_ = Path::kCopy;
  int block_x_ = 1, block_y_ = 1;           // kBlocks: the whole-number factors
  std::vector<AreaWeight> columns_, rows_;  // kWeighted: OpenCV's xtab and ytab
  std::vector<float> row_sum_, sum_;        // kWeighted: one destination row each
};

// One image through OpencvAreaResize (tests, single use).
void opencv_area_resize(std::span<const uint8_t> src, const ImageSize& from, int height, int width,
                        std::span<uint8_t> dst);

}  // namespace rlrun
