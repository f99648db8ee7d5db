// GripperLift's picture: the table (a checkered square, for depth), the cube (red), the palm
// and fingers (greys), seen from the front-right and above like panda-gym's default camera,
// flat shaded by one directional light, each box casting a hard shadow on the table (its
// corners projected along the light onto the table plane, the convex hull filled dark: the
// planar projected shadow of Blinn, "Me and My (Fake) Shadow", 1988).
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/rasterizer.hpp"

namespace rlrun {

namespace {

const Eigen::Vector3f kTowardsLight(0.35f, -0.25f, 1.0f);
constexpr float kShadowLift = 0.0005f;  // m above the table, so shadows win the depth test
constexpr float kTableHalf = 0.25f;
constexpr int kTiles = 10;

std::array<Eigen::Vector3f, 8> corners(const GripperWorld::BoxPose& box) {
  std::array<Eigen::Vector3f, 8> out;
  for (int i = 0; i < 8; ++i) {
    const double local[3] = {(i & 1 ? 1 : -1) * box.half[0], (i & 2 ? 1 : -1) * box.half[1],
                             (i & 4 ? 1 : -1) * box.half[2]};
    for (int r = 0; r < 3; ++r) {
      double v = box.centre[r];
      for (int c = 0; c < 3; ++c) v += box.rotation[3 * r + c] * local[c];
      out[i][r] = static_cast<float>(v);
    }
  }
  return out;
}

void draw_box(Rasterizer& raster, const GripperWorld::BoxPose& box, Rgb color) {
  const auto v = corners(box);
  // Faces by corner index bits (x = 1, y = 2, z = 4), two triangles each.
  static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : kFaces) {
    raster.triangle(v[f[0]], v[f[1]], v[f[2]], color);
    raster.triangle(v[f[0]], v[f[2]], v[f[3]], color);
  }
}

// 2D convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2f> hull(std::vector<Eigen::Vector2f> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2f> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k > 1 ? k - 1 : k);
  return h;
}

void draw_shadow(Rasterizer& raster, const GripperWorld::BoxPose& box) {
  const Eigen::Vector3f light = kTowardsLight.normalized();
  std::vector<Eigen::Vector2f> ground;
  for (const Eigen::Vector3f& c : corners(box)) {
    const float t = std::max(c.z(), 0.0f) / light.z();  // slide down the light ray to z = 0
    ground.emplace_back(c.x() - t * light.x(), c.y() - t * light.y());
  }
  const auto h = hull(ground);
  for (size_t i = 1; i + 1 < h.size(); ++i)
    raster.triangle({h[0].x(), h[0].y(), kShadowLift}, {h[i].x(), h[i].y(), kShadowLift},
                    {h[i + 1].x(), h[i + 1].y(), kShadowLift}, {70, 62, 52});
}

}  // namespace

bool GripperLift::render(Frame& frame) const {
  if (!world_) throw std::logic_error(id() + ": call reset() before render()");
  Rasterizer raster(frame);
  raster.set_camera(look_at({0.40f, -0.50f, 0.38f}, {0.0f, 0.0f, 0.09f}, {0, 0, 1}),
                    perspective(0.85f, static_cast<float>(frame.width()) / frame.height(), 0.05f, 5.0f));
  raster.set_light(kTowardsLight, 0.35f);
  raster.clear({205, 222, 238});  // pale sky
  // The table top, checkered.
  const float tile = 2 * kTableHalf / kTiles;
  for (int i = 0; i < kTiles; ++i)
    for (int j = 0; j < kTiles; ++j) {
      const float x = -kTableHalf + i * tile, y = -kTableHalf + j * tile;
      const Rgb color = (i + j) % 2 ? Rgb{196, 170, 130} : Rgb{181, 154, 114};
      raster.triangle({x, y, 0}, {x + tile, y, 0}, {x + tile, y + tile, 0}, color);
      raster.triangle({x, y, 0}, {x + tile, y + tile, 0}, {x, y + tile, 0}, color);
    }
  const GripperWorld& w = *world_;
  const auto fingers = w.finger_poses();
  for (const auto& box : {w.cube_pose(), w.palm_pose(), fingers[0], fingers[1]}) draw_shadow(raster, box);
  draw_box(raster, w.cube_pose(), success_ ? Rgb{40, 180, 70} : Rgb{200, 40, 40});
  draw_box(raster, w.palm_pose(), {150, 150, 160});
  for (const auto& finger : fingers) draw_box(raster, finger, {90, 90, 100});
  return true;
}

}  // namespace rlrun
