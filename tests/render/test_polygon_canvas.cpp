// PolygonCanvas (render/polygon_canvas.hpp): what its box filter must give for every
// supersampling factor, including the power-of-two ones it resolves with shifts, the others it
// divides, and the largest (16 x 16 samples of 255 must not carry between channels).
#include <catch2/catch.hpp>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "rlrun/render/polygon_canvas.hpp"

namespace rlrun {
namespace {

// The rounded mean of `covered` samples of colour b and the rest of a, as resolve() rounds it.
uint8_t mean(int a, int b, int covered, int count) {
  return static_cast<uint8_t>((a * (count - covered) + b * covered + count / 2) / count);
}

}  // namespace

TEST_CASE("PolygonCanvas resolves each pixel to the rounded mean of its samples", "[render]") {
  const Rgb background{255, 7, 200}, paint{0, 255, 13};
  for (int ss : {1, 2, 3, 4, 5, 16}) {
    INFO("supersample " << ss);
    PolygonCanvas canvas(3, 2, ss);
    canvas.clear(background);
    // Pixel (0, 0): its left half painted; pixel (2, 1): all of it; the rest background. A
    // sample (i, j) of a pixel sits at ((i + 0.5) / ss, (j + 0.5) / ss) inside it.
    canvas.rect(0.0, 0.0, 0.5, 1.0, paint);
    canvas.rect(2.0, 1.0, 3.0, 2.0, paint);
    std::vector<uint8_t> rgb(3 * 2 * 3);
    canvas.resolve(rgb);
    int half_columns = 0;
    for (int i = 0; i < ss; ++i) half_columns += (i + 0.5) / ss < 0.5;
    const int count = ss * ss, half = half_columns * ss;
    const auto pixel = [&](int x, int y, int channel) { return rgb[(y * 3 + x) * 3 + channel]; };
    CHECK(pixel(0, 0, 0) == mean(background.r, paint.r, half, count));
    CHECK(pixel(0, 0, 1) == mean(background.g, paint.g, half, count));
    CHECK(pixel(0, 0, 2) == mean(background.b, paint.b, half, count));
    CHECK(pixel(2, 1, 0) == paint.r);
    CHECK(pixel(2, 1, 1) == paint.g);
    CHECK(pixel(2, 1, 2) == paint.b);
    for (const auto& [x, y] : {std::pair{1, 0}, {2, 0}, {0, 1}, {1, 1}}) {
      CHECK(pixel(x, y, 0) == background.r);
      CHECK(pixel(x, y, 1) == background.g);
      CHECK(pixel(x, y, 2) == background.b);
    }
  }
}

TEST_CASE("PolygonCanvas: white stays white at the largest supersampling", "[render]") {
  PolygonCanvas canvas(2, 2, 16);
  canvas.clear({255, 255, 255});
  std::vector<uint8_t> rgb(2 * 2 * 3);
  canvas.resolve(rgb);
  for (const uint8_t v : rgb) CHECK(v == 255);
  CHECK_THROWS_AS(PolygonCanvas(2, 2, 17), std::invalid_argument);
  CHECK_THROWS_AS(canvas.resolve(std::span<uint8_t>(rgb.data(), 3)), std::invalid_argument);
}

}  // namespace rlrun
