// Frame: the Cairo canvas envs draw on (src/rlrun/render/frame.hpp).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "render/rgb_print.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/overlay.hpp"

using rlrun::Frame;
using rlrun::Point;
using rlrun::Rgb;

namespace {
const Rgb kWhite{255, 255, 255};
const Rgb kBlack{0, 0, 0};
const Rgb kRed{255, 0, 0};
}  // namespace

TEST_CASE("Frame fills, reads pixels and packs RGB", "[render]") {
  Frame frame(8, 6);
  CHECK(frame.width() == 8);
  CHECK(frame.height() == 6);
  frame.fill({10, 20, 30});
  CHECK(frame.pixel(0, 0) == Rgb{10, 20, 30});
  CHECK(frame.pixel(7, 5) == Rgb{10, 20, 30});
  std::vector<uint8_t> rgb;
  frame.to_rgb(rgb);
  REQUIRE(rgb.size() == 8 * 6 * 3);
  CHECK(rgb[0] == 10);
  CHECK(rgb[1] == 20);
  CHECK(rgb[2] == 30);
  CHECK_THROWS_AS(frame.pixel(8, 0), std::out_of_range);
  CHECK_THROWS_AS(Frame(0, 10), std::invalid_argument);
  CHECK_THROWS_AS(Frame(10, 100000), std::invalid_argument);
}

TEST_CASE("Frame scenes are y-up like Gymnasium's flipped pygame surface", "[render]") {
  Frame frame(600, 400);
  frame.begin_scene(600, 400, kWhite);
  const Point square[] = {{0, 0}, {0, 10}, {10, 10}, {10, 0}};
  frame.polygon(square, kRed);
  frame.end_scene();
  CHECK(frame.pixel(5, 395) == kRed);  // scene y = 5 is near the bottom row
  CHECK(frame.pixel(5, 5) == kWhite);
  CHECK(frame.pixel(15, 395) == kWhite);
}

TEST_CASE("Frame scenes scale uniformly and letterbox", "[render]") {
  // A 500x500 scene in a 600x400 frame: scale 0.8, centred with 100 px margins left and right.
  Frame frame(600, 400);
  frame.fill(kRed);
  frame.begin_scene(500, 500, kWhite);
  CHECK(frame.scene_scale() == Approx(0.8));
  const Point everything[] = {{0, 0}, {0, 500}, {500, 500}, {500, 0}};
  frame.polygon(everything, kBlack);
  frame.end_scene();
  CHECK(frame.pixel(50, 200) == kWhite);  // margin: background, not red, not drawn on
  CHECK(frame.pixel(550, 200) == kWhite);
  CHECK(frame.pixel(105, 200) == kBlack);  // inside the scene
  CHECK(frame.pixel(495, 200) == kBlack);
}

TEST_CASE("Frame circles and lines are drawn where asked", "[render]") {
  Frame frame(100, 100);
  frame.begin_scene(100, 100, kWhite, /*y_up=*/false);
  frame.circle({50, 50}, 10, kRed);
  frame.line({0, 80.5}, {100, 80.5}, kBlack, 1.0);
  frame.end_scene();
  CHECK(frame.pixel(50, 50) == kRed);
  CHECK(frame.pixel(57, 50) == kRed);
  CHECK(frame.pixel(62, 50) == kWhite);
  CHECK(frame.pixel(30, 80) == kBlack);
  CHECK(frame.pixel(30, 78) == kWhite);
}

TEST_CASE("Frame writes PNG files", "[render]") {
  const auto path = std::filesystem::temp_directory_path() / "rlrun_test_frame.png";
  Frame frame(16, 16);
  frame.fill(kRed);
  frame.write_png(path.string());
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  CHECK(std::string(magic + 1, 3) == "PNG");
  std::filesystem::remove(path);
  CHECK_THROWS(frame.write_png("/nonexistent-dir/x.png"));
}

TEST_CASE("Text overlay darkens the top-left corner and leaves the rest", "[render]") {
  Frame frame(600, 400);
  frame.fill(kWhite);
  rlrun::draw_text_overlay(frame, {"CartPole-v1", "episode 1/1  step 3", "return 3.00"});
  const Rgb corner = frame.pixel(2, 2);
  CHECK(corner.r < 200);  // translucent dark box
  CHECK(frame.pixel(599, 399) == kWhite);
  // Some text pixels are light inside the box.
  bool light = false;
  for (int y = 0; y < 40 && !light; ++y)
    for (int x = 0; x < 120 && !light; ++x) light = frame.pixel(x, y).r > 200;
  CHECK(light);
}

TEST_CASE("Text overlay keeps to the left 40 % of the frame, splitting wide lines", "[render]") {
  // A recorded traffic video's lines: the box once reached past the middle, over the road.
  Frame frame(600, 600);
  frame.fill(kWhite);
  rlrun::draw_text_overlay(frame, {"TrafficSignal-v0  DQN deterministic",
                                   "episode 10/10  step 1000", "return -1234.00"});
  for (int y = 0; y < 600; ++y)
    for (int x = 240; x < 600; ++x) REQUIRE(frame.pixel(x, y) == kWhite);
  CHECK(frame.pixel(2, 2).r < 200);
  // Short lines are left as they were: one line of text, one line of box.
  Frame small(600, 400);
  small.fill(kWhite);
  rlrun::draw_text_overlay(small, {"CartPole-v1  PPO"});
  CHECK(small.pixel(2, 2).r < 200);
  CHECK(small.pixel(2, 40) == kWhite);
}
