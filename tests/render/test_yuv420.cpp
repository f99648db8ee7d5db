// RGB -> yuv420p conversion for the video pipe (src/rlrun/render/yuv420.hpp): BT.601
// limited range; the expected values are the 8-bit ones of BT.601 colour bars (green Y is
// 144 here, 144.55 exactly, which the integer coefficients round down).
#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/frame.hpp"
#include "rlrun/render/yuv420.hpp"

namespace {

std::vector<uint8_t> convert(const rlrun::Frame& frame) {
  std::vector<uint8_t> out(static_cast<size_t>(frame.width()) * frame.height() * 3 / 2);
  rlrun::rgb24_to_yuv420p(frame.pixels(), frame.stride_pixels(), frame.width(), frame.height(),
                          out.data());
  return out;
}

}  // namespace

TEST_CASE("yuv420p of flat colours has BT.601 limited-range values", "[render]") {
  struct Case {
    rlrun::Rgb rgb;
    int y, u, v;
  };
  const Case cases[] = {{{255, 255, 255}, 235, 128, 128},
                        {{0, 0, 0}, 16, 128, 128},
                        {{255, 0, 0}, 82, 90, 240},
                        {{0, 255, 0}, 144, 54, 34},
                        {{0, 0, 255}, 41, 240, 110}};
  for (const Case& c : cases) {
    rlrun::Frame frame(4, 2);
    frame.fill(c.rgb);
    const auto yuv = convert(frame);
    REQUIRE(yuv.size() == 12);
    CHECK(int(yuv[0]) == c.y);
    CHECK(int(yuv[7]) == c.y);
    CHECK(int(yuv[8]) == c.u);   // U plane: 2 values
    CHECK(int(yuv[10]) == c.v);  // V plane: 2 values
  }
}

TEST_CASE("yuv420p chroma averages each 2x2 block", "[render]") {
  rlrun::Frame frame(2, 2);
  frame.fill({255, 255, 255});
  uint32_t* p = frame.pixels();
  p[0] = 0x000000;  // one black pixel of four
  frame.mark_dirty();
  const auto yuv = convert(frame);
  CHECK(int(yuv[0]) == 16);
  CHECK(int(yuv[1]) == 235);
  CHECK(int(yuv[4]) == 128);  // grey average: no chroma
  CHECK(int(yuv[5]) == 128);
}
