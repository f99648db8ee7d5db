#include "rlrun/envs/gripper/gripper_scene_render.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rlrun {

namespace {

const Eigen::Vector3f kTowardsLight(0.35f, -0.25f, 1.0f);
constexpr float kShadowLift = 0.0005f;  // m above the table, so shadows win the depth test
constexpr float kTableHalf = 0.25f;
constexpr int kTiles = 10;
constexpr int kSphereSlices = 12, kSphereStacks = 8;

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

// 2D convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2f> hull(std::vector<Eigen::Vector2f> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const Eigen::Vector2f& o, const Eigen::Vector2f& a,
                        const Eigen::Vector2f& b) {
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

// The shadow of a convex shape given by its points: their projections along the light onto
// the table, hull filled.
void draw_shadow(Rasterizer& raster, std::span<const Eigen::Vector3f> points) {
  const Eigen::Vector3f light = kTowardsLight.normalized();
  std::vector<Eigen::Vector2f> ground;
  for (const Eigen::Vector3f& c : points) {
    const float t = std::max(c.z(), 0.0f) / light.z();  // slide down the light ray to z = 0
    ground.emplace_back(c.x() - t * light.x(), c.y() - t * light.y());
  }
  const auto h = hull(ground);
  for (size_t i = 1; i + 1 < h.size(); ++i)
    raster.triangle({h[0].x(), h[0].y(), kShadowLift}, {h[i].x(), h[i].y(), kShadowLift},
                    {h[i + 1].x(), h[i + 1].y(), kShadowLift}, {70, 62, 52});
}

// A unit sphere: poles and kSphereStacks - 1 rings of kSphereSlices points.
struct SphereMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::array<int, 3>> triangles;
  SphereMesh() {
    vertices.emplace_back(0.0f, 0.0f, 1.0f);
    for (int i = 1; i < kSphereStacks; ++i) {
      const double polar = M_PI * i / kSphereStacks;
      for (int j = 0; j < kSphereSlices; ++j) {
        const double azimuth = 2 * M_PI * j / kSphereSlices;
        vertices.emplace_back(static_cast<float>(std::sin(polar) * std::cos(azimuth)),
                              static_cast<float>(std::sin(polar) * std::sin(azimuth)),
                              static_cast<float>(std::cos(polar)));
      }
    }
    vertices.emplace_back(0.0f, 0.0f, -1.0f);
    const int bottom = static_cast<int>(vertices.size()) - 1;
    const auto ring = [](int i, int j) { return 1 + (i - 1) * kSphereSlices + j % kSphereSlices; };
    for (int j = 0; j < kSphereSlices; ++j) {
      triangles.push_back({0, ring(1, j), ring(1, j + 1)});
      for (int i = 1; i + 1 < kSphereStacks; ++i) {
        triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
        triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
      }
      triangles.push_back({ring(kSphereStacks - 1, j), bottom, ring(kSphereStacks - 1, j + 1)});
    }
  }
};

const SphereMesh& sphere_mesh() {
  static const SphereMesh mesh;
  return mesh;
}

}  // namespace

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

void draw_box_shadow(Rasterizer& raster, const GripperWorld::BoxPose& box) {
  const auto c = corners(box);
  draw_shadow(raster, c);
}

void draw_sphere(Rasterizer& raster, const Vec3& centre, double radius, Rgb color) {
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
  model.topLeftCorner<3, 3>() *= static_cast<float>(radius);
  model.topRightCorner<3, 1>() = Eigen::Vector3d(centre[0], centre[1], centre[2]).cast<float>();
  const SphereMesh& mesh = sphere_mesh();
  raster.mesh(mesh.vertices, mesh.triangles, model, color);
}

void draw_sphere_shadow(Rasterizer& raster, const Vec3& centre, double radius) {
  std::vector<Eigen::Vector3f> points;
  const Eigen::Vector3f c = Eigen::Vector3d(centre[0], centre[1], centre[2]).cast<float>();
  for (const Eigen::Vector3f& v : sphere_mesh().vertices)
    points.push_back(c + static_cast<float>(radius) * v);
  draw_shadow(raster, points);
}

void draw_gripper_scene(Rasterizer& raster, const Frame& frame, const GripperWorld& world,
                        const GripperCamera& camera, Rgb cube_color) {
  raster.set_camera(look_at(camera.eye, camera.target, {0, 0, 1}),
                    perspective(camera.fov_y, static_cast<float>(frame.width()) / frame.height(),
                                camera.near, 5.0f));
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
  const auto fingers = world.finger_poses();
  if (world.has_cube()) draw_box_shadow(raster, world.cube_pose());
  for (const auto& box : {world.palm_pose(), fingers[0], fingers[1]}) draw_box_shadow(raster, box);
  if (world.has_cube()) draw_box(raster, world.cube_pose(), cube_color);
  draw_box(raster, world.palm_pose(), {150, 150, 160});
  for (const auto& finger : fingers) draw_box(raster, finger, {90, 90, 100});
}

}  // namespace rlrun
