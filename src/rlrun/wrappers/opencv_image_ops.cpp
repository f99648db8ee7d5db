#include "rlrun/wrappers/opencv_image_ops.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

namespace {

// saturate_cast<uchar>(float): cvRound (to nearest, ties to even), then clamped.
uint8_t round_to_u8(float v) {
  const long rounded = std::lrint(v);
  return static_cast<uint8_t>(std::clamp<long>(rounded, 0, 255));
}

// hal::resize's scales: 1 / (destination / source); "integer" means within DBL_EPSILON of the
// rounded value, as OpenCV decides whether whole blocks are averaged.
struct AreaScales {
  double x, y;
  int integer_x, integer_y;
  bool whole_blocks;
};
AreaScales area_scales(const ImageSize& from, int height, int width) {
  AreaScales s;
  s.x = 1.0 / (static_cast<double>(width) / from.width);
  s.y = 1.0 / (static_cast<double>(height) / from.height);
  s.integer_x = static_cast<int>(std::lrint(s.x));
  s.integer_y = static_cast<int>(std::lrint(s.y));
  s.whole_blocks =
      std::abs(s.x - s.integer_x) < DBL_EPSILON && std::abs(s.y - s.integer_y) < DBL_EPSILON;
  return s;
}

}  // namespace

uint8_t opencv_rgb_to_gray(uint8_t r, uint8_t g, uint8_t b) {
  return static_cast<uint8_t>((9798 * r + 19235 * g + 3735 * b + (1 << 14)) >> 15);
}

std::string opencv_area_resize_refusal(const ImageSize& from, int height, int width) {
  const std::string sizes = std::to_string(from.height) + "x" + std::to_string(from.width) +
                            " to " + std::to_string(height) + "x" + std::to_string(width);
  if (height < 1 || width < 1 || height > from.height || width > from.width)
    return "INTER_AREA resizing from " + sizes +
           ": rlrun implements OpenCV's area path, which only shrinks (no side may grow)";
  if (from.channels > 4 && !(height == from.height && width == from.width) &&
      !area_scales(from, height, width).whole_blocks)
    return "INTER_AREA resizing " + std::to_string(from.channels) + " channels from " + sizes +
           ": OpenCV handles more than 4 channels only at whole-number factors (it asserts cn <= "
           "4)";
  return "";
}

// computeResizeAreaTab: for each destination index, the source indices its cell [d * scale,
// (d + 1) * scale) covers and the covered fraction of each, divided by the cell's width; a
// partly covered pixel counts only if more than 1e-3 of it is inside.
std::vector<OpencvAreaResize::AreaWeight> OpencvAreaResize::area_weights(int source_size,
                                                                         int destination_size,
                                                                         int channels,
                                                                         double scale) {
  std::vector<AreaWeight> weights;
  for (int d = 0; d < destination_size; ++d) {
    const double start = d * scale;
    const double end = start + scale;
    const double cell = std::min(scale, source_size - start);
    int first = static_cast<int>(std::ceil(start));
    int last = static_cast<int>(std::floor(end));
    last = std::min(last, source_size - 1);
    first = std::min(first, last);
    if (first - start > 1e-3)
      weights.push_back(
          {d * channels, (first - 1) * channels, static_cast<float>((first - start) / cell)});
    for (int s = first; s < last; ++s)
      weights.push_back({d * channels, s * channels, static_cast<float>(1.0 / cell)});
    if (end - last > 1e-3)
      weights.push_back({d * channels, last * channels,
                         static_cast<float>(std::min(std::min(end - last, 1.0), cell) / cell)});
  }
  return weights;
}

OpencvAreaResize::OpencvAreaResize(const ImageSize& from, int height, int width)
    : from_(from), height_(height), width_(width) {
  if (const std::string refusal = opencv_area_resize_refusal(from, height, width); !refusal.empty())
    throw std::invalid_argument(refusal);
  if (height == from.height && width == from.width) return;  // cv::resize copies
  const AreaScales s = area_scales(from, height, width);
  if (!s.whole_blocks) {
    path_ = Path::kWeighted;
    columns_ = area_weights(from.width, width, from.channels, s.x);
    rows_ = area_weights(from.height, height, 1, s.y);
    row_sum_.resize(static_cast<size_t>(width) * from.channels);
    sum_.resize(row_sum_.size());
  } else if (s.integer_x == 2 && s.integer_y == 2 &&
             (from.channels == 1 || from.channels == 3 || from.channels == 4)) {
    path_ = Path::kHalve;
  } else {
    path_ = Path::kBlocks;
    block_x_ = s.integer_x;
    block_y_ = s.integer_y;
  }
}

void OpencvAreaResize::operator()(std::span<const uint8_t> src, std::span<uint8_t> dst) {
  if (static_cast<int64_t>(src.size()) != from_.values() ||
      static_cast<int64_t>(dst.size()) != int64_t{height_} * width_ * from_.channels)
    throw std::invalid_argument("OpencvAreaResize: buffer sizes do not match the images");
  switch (path_) {
    case Path::kCopy: std::copy(src.begin(), src.end(), dst.begin()); break;
    case Path::kHalve: halve(src, dst); break;
    case Path::kBlocks: average_blocks(src, dst); break;
    case Path::kWeighted: weighted_area(src, dst); break;
  }
}

// resizeAreaFast with 2x2 blocks of 1, 3 or 4 channels: OpenCV's vector path, rounding half up.
void OpencvAreaResize::halve(std::span<const uint8_t> src, std::span<uint8_t> dst) const {
  const int c = from_.channels;
  const size_t row = static_cast<size_t>(from_.width) * c;
  for (int y = 0; y < height_; ++y) {
    const uint8_t* top = src.data() + static_cast<size_t>(2 * y) * row;
    const uint8_t* bottom = top + row;
    uint8_t* out = dst.data() + static_cast<size_t>(y) * width_ * c;
    for (int x = 0; x < width_; ++x)
      for (int k = 0; k < c; ++k) {
        const int i = 2 * x * c + k;
        out[x * c + k] =
            static_cast<uint8_t>((top[i] + top[i + c] + bottom[i] + bottom[i + c] + 2) >> 2);
      }
  }
}

// resizeAreaFast_Invoker's scalar loop: an integer sum over each block, times 1/area in float.
void OpencvAreaResize::average_blocks(std::span<const uint8_t> src, std::span<uint8_t> dst) const {
  const int c = from_.channels;
  const size_t row = static_cast<size_t>(from_.width) * c;
  const float inverse_area = 1.f / static_cast<float>(block_x_ * block_y_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int k = 0; k < c; ++k) {
        int sum = 0;
        for (int by = 0; by < block_y_; ++by)
          for (int bx = 0; bx < block_x_; ++bx)
            sum += src[static_cast<size_t>(y * block_y_ + by) * row +
                       static_cast<size_t>(x * block_x_ + bx) * c + k];
        dst[(static_cast<size_t>(y) * width_ + x) * c + k] =
            round_to_u8(static_cast<float>(sum) * inverse_area);
      }
}

// resizeArea_Invoker: each source row's weighted columns into `row_sum_`, rows weighted into
// `sum_`; a destination row is written when the next source row belongs to the next one.
void OpencvAreaResize::weighted_area(std::span<const uint8_t> src, std::span<uint8_t> dst) {
  const int c = from_.channels;
  const size_t out_row = sum_.size();
  std::fill(sum_.begin(), sum_.end(), 0.f);
  int current = rows_.front().destination;
  auto write = [&](int y) {
    for (size_t i = 0; i < out_row; ++i) dst[y * out_row + i] = round_to_u8(sum_[i]);
  };
  for (const AreaWeight& r : rows_) {
    const uint8_t* s = src.data() + static_cast<size_t>(r.source) * from_.width * c;
    std::fill(row_sum_.begin(), row_sum_.end(), 0.f);
    for (const AreaWeight& w : columns_)
      for (int k = 0; k < c; ++k) row_sum_[w.destination + k] += s[w.source + k] * w.alpha;
    const float beta = r.alpha;
    if (r.destination != current) {
      write(current);
      for (size_t i = 0; i < out_row; ++i) sum_[i] = beta * row_sum_[i];
      current = r.destination;
    } else {
      for (size_t i = 0; i < out_row; ++i) sum_[i] += beta * row_sum_[i];
    }
  }
  write(current);
}

void opencv_area_resize(std::span<const uint8_t> src, const ImageSize& from, int height, int width,
                        std::span<uint8_t> dst) {
  OpencvAreaResize(from, height, width)(src, dst);
}

}  // namespace rlrun
