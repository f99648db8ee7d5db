// The z-buffered triangle rasterizer (src/rlrun/render/rasterizer.hpp), on its own.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "render/rgb_print.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/overlay.hpp"
#include "rlrun/render/rasterizer.hpp"

using Eigen::Matrix4f;
using Eigen::Vector3f;
using rlrun::Frame;
using rlrun::Rasterizer;
using rlrun::Rgb;

namespace {

const Rgb kWhite{255, 255, 255};
const Rgb kRed{200, 0, 0};
const Rgb kBlue{0, 0, 200};

// Identity camera: world coordinates are NDC (x, y in [-1, 1]); depth (z + 1) / 2. Full light
// so colours come out unchanged.
void ndc_camera(Rasterizer& r) {
  r.set_camera(Matrix4f::Identity(), Matrix4f::Identity());
  r.set_light({0, 0, 1}, 1.0f);
}

}  // namespace

TEST_CASE("Rasterizer: the nearer triangle wins whatever the drawing order", "[render]") {
  for (bool near_first : {true, false}) {
    Frame frame(64, 64);
    Rasterizer r(frame);
    ndc_camera(r);
    r.clear(kWhite);
    auto near = [&] {
      r.triangle({-0.8f, -0.8f, -0.5f}, {0.8f, -0.8f, -0.5f}, {0, 0.8f, -0.5f}, kRed);
    };
    auto far = [&] {
      r.triangle({-0.8f, 0.8f, 0.5f}, {0.8f, 0.8f, 0.5f}, {0, -0.8f, 0.5f}, kBlue);
    };
    if (near_first) {
      near();
      far();
    } else {
      far();
      near();
    }
    CHECK(frame.pixel(32, 32) == kRed);    // overlap: near (z = -0.5) in front
    CHECK(frame.pixel(32, 60) == kWhite);  // below both
    CHECK(r.depth(32, 32) == Approx(0.25f));
    CHECK(std::isinf(r.depth(1, 1)));
  }
}

TEST_CASE("Rasterizer: two triangles sharing an edge cover every pixel exactly once", "[render]") {
  // The second triangle is nearer: a pixel of the shared diagonal drawn by both would be
  // counted twice. The top-left rule gives each such pixel to exactly one triangle.
  Frame frame(37, 23);  // odd sizes: the diagonal crosses pixel centres unevenly
  Rasterizer r(frame);
  ndc_camera(r);
  r.clear(kWhite);
  r.triangle({-1, -1, 0.2f}, {1, -1, 0.2f}, {1, 1, 0.2f}, kRed);
  r.triangle({-1, -1, 0.1f}, {1, 1, 0.1f}, {-1, 1, 0.1f}, kBlue);
  CHECK(r.pixels_written() == 37 * 23);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) REQUIRE_FALSE(frame.pixel(x, y) == kWhite);
}

TEST_CASE("Rasterizer: perspective cube, near-plane clipping, Cairo on top", "[render]") {
  Frame frame(160, 120);
  Rasterizer r(frame);
  r.set_camera(rlrun::look_at({3, 2.5f, 4}, {0, 0, 0}, {0, 1, 0}),
               rlrun::perspective(std::numbers::pi_v<float> / 4, 160.0f / 120, 0.1f, 100));
  r.set_light({0.3f, 1, 0.5f}, 0.3f);
  r.clear(kWhite);
  const Vector3f v[] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                        {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const std::array<int, 3> t[] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                  {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  r.mesh(v, t, Matrix4f::Identity(), {200, 120, 40});
  // The cube is in the middle of the picture, the corners are background.
  CHECK_FALSE(frame.pixel(80, 60) == kWhite);
  CHECK(frame.pixel(0, 0) == kWhite);
  CHECK(frame.pixel(159, 119) == kWhite);
  // Flat shading: the three visible faces (top, front, right) have different brightness.
  std::set<int> shades;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      if (!(frame.pixel(x, y) == kWhite)) shades.insert(frame.pixel(x, y).r);
  CHECK(shades.size() >= 3);
  CHECK_THROWS_AS(r.mesh(v, std::vector<std::array<int, 3>>{{0, 1, 8}}, Matrix4f::Identity(), kRed),
                  std::out_of_range);

  // Cairo annotates the rasterized picture.
  const Rgb centre = frame.pixel(80, 60);
  rlrun::draw_text_overlay(frame, {"step 1"});
  CHECK(frame.pixel(80, 60) == centre);
  CHECK(frame.pixel(1, 1).r < 150);
}

TEST_CASE("Rasterizer: triangles behind the camera are clipped away", "[render]") {
  Frame frame(100, 100);
  Rasterizer r(frame);
  r.set_camera(rlrun::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}),
               rlrun::perspective(std::numbers::pi_v<float> / 2, 1.0f, 0.1f, 100));
  r.set_light({0, 0, 1}, 1.0f);
  r.clear(kWhite);
  // Entirely behind the camera (z > 5): nothing.
  r.triangle({-1, -1, 7}, {1, -1, 7}, {0, 1, 7}, kBlue);
  CHECK(r.pixels_written() == 0);
  // Through the camera plane: only the part in front of the near plane is drawn, and the
  // vertex behind the camera does not flip it across the picture.
  r.triangle({-1, -1, 0}, {1, -1, 0}, {0, -1, 10}, kBlue);
  CHECK(r.pixels_written() > 0);
  CHECK(frame.pixel(50, 80) == kBlue);   // below the centre: the floor-like strip
  CHECK(frame.pixel(50, 20) == kWhite);  // nothing above the horizon
}
