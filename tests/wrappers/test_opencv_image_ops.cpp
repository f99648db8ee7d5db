// OpenCV's RGB2GRAY and INTER_AREA resize, bit for bit: every output byte against what Debian's
// OpenCV 4.6 printed for the same deterministic images (tests/data/opencv/golden.txt, made by
// scripts/tests/make_opencv_golden.py with cv2 itself).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/wrappers/opencv_image_ops.hpp"
#include "test_paths.hpp"

namespace rlrun {
namespace {

// The script's images: a 64-bit LCG, one pixel per step, the top byte.
std::vector<uint8_t> lcg_image(int64_t values, uint64_t seed) {
  std::vector<uint8_t> image(static_cast<size_t>(values));
  uint64_t x = seed;
  for (uint8_t& v : image) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    v = static_cast<uint8_t>(x >> 56);
  }
  return image;
}

std::vector<uint8_t> from_hex(const std::string& hex) {
  std::vector<uint8_t> bytes;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    bytes.push_back(static_cast<uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return bytes;
}

std::vector<std::string> golden_lines(const std::string& operation) {
  std::ifstream in(std::string(test_paths::source_dir()) + "/tests/data/opencv/golden.txt");
  REQUIRE(in);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (line.rfind(operation + " ", 0) == 0) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("INTER_AREA resizing matches OpenCV's bytes", "[wrappers][image][opencv]") {
  const std::vector<std::string> lines = golden_lines("resize");
  REQUIRE(lines.size() >= 16);
  for (const std::string& line : lines) {
    std::istringstream fields(line);
    std::string operation, hex;
    ImageSize from;
    int height = 0, width = 0;
    uint64_t seed = 0;
    fields >> operation >> from.height >> from.width >> from.channels >> height >> width >> seed >>
        hex;
    INFO(line.substr(0, 40));
    const std::vector<uint8_t> src = lcg_image(from.values(), seed);
    std::vector<uint8_t> dst(static_cast<size_t>(height) * width * from.channels);
    REQUIRE(opencv_area_resize_refusal(from, height, width).empty());
    opencv_area_resize(src, from, height, width, dst);
    const std::vector<uint8_t> expected = from_hex(hex);
    REQUIRE(expected.size() == dst.size());
    size_t differing = 0;
    for (size_t i = 0; i < dst.size(); ++i) differing += dst[i] != expected[i];
    CHECK(differing == 0);
  }
}

TEST_CASE("RGB2GRAY matches OpenCV's bytes", "[wrappers][image][opencv]") {
  const std::vector<std::string> lines = golden_lines("gray");
  REQUIRE(lines.size() == 2);
  for (const std::string& line : lines) {
    std::istringstream fields(line);
    std::string operation, hex;
    int height = 0, width = 0;
    uint64_t seed = 0;
    fields >> operation >> height >> width >> seed >> hex;
    const std::vector<uint8_t> rgb = lcg_image(int64_t{height} * width * 3, seed);
    const std::vector<uint8_t> expected = from_hex(hex);
    REQUIRE(expected.size() == static_cast<size_t>(height) * width);
    for (size_t p = 0; p < expected.size(); ++p)
      REQUIRE(opencv_rgb_to_gray(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]) == expected[p]);
  }
  // The corners of the cube: white stays 255 (Gymnasium 1.0's float weights give 254).
  CHECK(opencv_rgb_to_gray(255, 255, 255) == 255);
  CHECK(opencv_rgb_to_gray(0, 0, 0) == 0);
}

TEST_CASE("INTER_AREA refuses what OpenCV's area path does not do", "[wrappers][image][opencv]") {
  const ImageSize rgb{96, 96, 3};
  CHECK_THAT(opencv_area_resize_refusal(rgb, 100, 96), Catch::Contains("only shrinks"));
  CHECK_THAT(opencv_area_resize_refusal(rgb, 0, 10), Catch::Contains("only shrinks"));
  const ImageSize stacked{96, 96, 8};
  CHECK_THAT(opencv_area_resize_refusal(stacked, 64, 64), Catch::Contains("cn <= 4"));
  CHECK(opencv_area_resize_refusal(stacked, 48, 48).empty());  // whole 2x2 blocks: allowed
  std::vector<uint8_t> src(96 * 96 * 3), dst(100 * 96 * 3);
  CHECK_THROWS_AS(opencv_area_resize(src, rgb, 100, 96, dst), std::invalid_argument);
  // Pixels of a float observation are read as the uint8 Box holds them.
  CHECK(opencv_pixel(-3.f) == 0);
  CHECK(opencv_pixel(254.6f) == 255);
  CHECK(opencv_pixel(300.f) == 255);
  CHECK(opencv_pixel(17.f) == 17);
  CHECK(opencv_pixel(2.5f) == 2);  // ties to even, as lrint
  CHECK(opencv_pixel(3.5f) == 4);
  CHECK(opencv_pixel(std::nanf("")) == 0);
}

}  // namespace rlrun
