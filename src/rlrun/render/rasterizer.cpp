#include "rlrun/render/rasterizer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rlrun {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

uint32_t pack(Rgb c, float intensity) {
  auto channel = [intensity](uint8_t v) {
    return static_cast<uint32_t>(std::clamp(v * intensity + 0.5f, 0.0f, 255.0f));
  };
  return channel(c.r) << 16 | channel(c.g) << 8 | channel(c.b);
}

// Twice the signed area of (a, b, p); positive when p is on the inner side of edge a->b for
// triangles wound the way raster() arranges them.
inline float edge(float ax, float ay, float bx, float by, float px, float py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Top-left fill rule (Direct3D / OpenGL rasterization rules): a pixel centre exactly on an
// edge belongs to the triangle only if the edge is a top edge or a left edge, so two
// triangles sharing an edge never both draw it. With the winding raster() uses (y down),
// left edges go up (dy < 0) and top edges go right (dy == 0, dx > 0).
inline bool top_left(float dx, float dy) { return dy < 0 || (dy == 0 && dx > 0); }

}  // namespace

Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                        const Eigen::Vector3f& up) {
  const Eigen::Vector3f f = (target - eye).normalized();
  const Eigen::Vector3f s = f.cross(up).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f perspective(float fov_y_radians, float aspect, float near, float far) {
  if (!(near > 0 && far > near && aspect > 0 && fov_y_radians > 0))
    throw std::invalid_argument("perspective: needs 0 < near < far, aspect > 0 and fov > 0");
  const float f = 1.0f / std::tan(fov_y_radians / 2);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2 * far * near / (near - far);
  m(3, 2) = -1;
  return m;
}

Rasterizer::Rasterizer(Frame& frame)
    : frame_(frame),
      width_(frame.width()),
      height_(frame.height()),
      depth_(static_cast<size_t>(frame.width()) * frame.height(), kInf) {}

void Rasterizer::set_camera(const Eigen::Matrix4f& view, const Eigen::Matrix4f& projection) {
  view_ = view;
  view_projection_ = projection * view;
  // The camera sits where the view transform sends the origin from: -R^T t.
  eye_ = -view.block<3, 3>(0, 0).transpose() * view.block<3, 1>(0, 3);
}

void Rasterizer::set_light(const Eigen::Vector3f& towards_light, float ambient) {
  towards_light_ = towards_light.normalized();
  ambient_ = std::clamp(ambient, 0.0f, 1.0f);
}

void Rasterizer::clear(Rgb background) {
  frame_.end_scene();
  frame_.fill(background);
  clear_depth();
}

void Rasterizer::clear_depth() {
  std::fill(depth_.begin(), depth_.end(), kInf);
  pixels_written_ = 0;
}

void Rasterizer::triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                          const Eigen::Vector3f& c, Rgb color) {
  Eigen::Vector3f normal = (b - a).cross(c - a);
  const float length = normal.norm();
  if (!(length > 0)) return;  // degenerate
  normal /= length;
  if (normal.dot(eye_ - a) < 0) normal = -normal;  // two-sided: light the visible face
  const float intensity = ambient_ + (1 - ambient_) * std::max(0.0f, normal.dot(towards_light_));
  const uint32_t packed = pack(color, intensity);

  // Clip against the near plane (z_clip >= -w_clip) with Sutherland-Hodgman: a triangle
  // becomes at most a quad, drawn as a fan.
  const Eigen::Vector4f in[3] = {view_projection_ * a.homogeneous(),
                                 view_projection_ * b.homogeneous(),
                                 view_projection_ * c.homogeneous()};
  Eigen::Vector4f out[4];
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector4f& p = in[i];
    const Eigen::Vector4f& q = in[(i + 1) % 3];
    const float dp = p.z() + p.w(), dq = q.z() + q.w();
    if (dp >= 0) out[n++] = p;
    if ((dp >= 0) != (dq >= 0)) out[n++] = p + (q - p) * (dp / (dp - dq));
  }
  if (n < 3) return;
  const ScreenVertex s0 = to_screen(out[0]);
  for (int i = 1; i + 1 < n; ++i) raster(s0, to_screen(out[i]), to_screen(out[i + 1]), packed);
}

void Rasterizer::mesh(std::span<const Eigen::Vector3f> vertices,
                      std::span<const std::array<int, 3>> triangles, const Eigen::Matrix4f& model,
                      Rgb color) {
  std::vector<Eigen::Vector3f> world(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i)
    world[i] = (model * vertices[i].homogeneous()).hnormalized();
  for (const auto& t : triangles) {
    for (int index : t)
      if (index < 0 || static_cast<size_t>(index) >= world.size())
        throw std::out_of_range("mesh: vertex index " + std::to_string(index) + " of " +
                                std::to_string(world.size()));
    triangle(world[t[0]], world[t[1]], world[t[2]], color);
  }
}

Rasterizer::ScreenVertex Rasterizer::to_screen(const Eigen::Vector4f& clip) const {
  const float w = std::max(clip.w(), 1e-12f);
  return {(clip.x() / w + 1) * 0.5f * width_, (1 - clip.y() / w) * 0.5f * height_,
          (clip.z() / w + 1) * 0.5f};
}

void Rasterizer::raster(const ScreenVertex& a, const ScreenVertex& b0, const ScreenVertex& c0,
                        uint32_t color) {
  float area = edge(a.x, a.y, b0.x, b0.y, c0.x, c0.y);
  if (!(std::abs(area) > 1e-12f)) return;
  // Wind every triangle the same way so one inside test and one fill rule serve all.
  const bool flip = area < 0;
  const ScreenVertex& b = flip ? c0 : b0;
  const ScreenVertex& c = flip ? b0 : c0;
  area = std::abs(area);

  const int x_min = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x_max = std::min(width_ - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y_min = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y_max = std::min(height_ - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  if (x_min > x_max || y_min > y_max) return;

  const bool tl_bc = top_left(c.x - b.x, c.y - b.y);
  const bool tl_ca = top_left(a.x - c.x, a.y - c.y);
  const bool tl_ab = top_left(b.x - a.x, b.y - a.y);
  const float inv_area = 1.0f / area;
  uint32_t* pixels = frame_.pixels();
  const int stride = frame_.stride_pixels();
  for (int y = y_min; y <= y_max; ++y) {
    const float py = y + 0.5f;
    for (int x = x_min; x <= x_max; ++x) {
      const float px = x + 0.5f;
      const float w0 = edge(b.x, b.y, c.x, c.y, px, py);  // weight of a
      const float w1 = edge(c.x, c.y, a.x, a.y, px, py);  // weight of b
      const float w2 = edge(a.x, a.y, b.x, b.y, px, py);  // weight of c
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      if ((w0 == 0 && !tl_bc) || (w1 == 0 && !tl_ca) || (w2 == 0 && !tl_ab)) continue;
      const float z = (w0 * a.z + w1 * b.z + w2 * c.z) * inv_area;
      if (z < 0 || z > 1) continue;  // outside the near/far range
      float& d = depth_[static_cast<size_t>(y) * width_ + x];
      if (z >= d) continue;
      d = z;
      pixels[static_cast<size_t>(y) * stride + x] = color;
      ++pixels_written_;
    }
  }
  frame_.mark_dirty();
}

}  // namespace rlrun
