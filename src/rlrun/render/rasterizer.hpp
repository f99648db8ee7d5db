#pragma once
// A small z-buffered triangle rasterizer for 3D scenes (the Bullet grasp task), drawing
// straight into a Frame so Cairo can annotate the result afterwards. CPU only, no GPU or
// display. The pipeline is the textbook one (e.g. Marschner & Shirley, "Fundamentals of
// Computer Graphics", ch. 8-9; OpenGL's conventions for the matrices):
//   world --view--> camera --projection--> clip space --near-plane clip--> NDC --> pixels,
// then edge functions over the triangle's bounding box with the top-left fill rule (no
// pixel of a shared edge is drawn twice), depth interpolated linearly in screen space
// (NDC z is affine there) and tested per pixel. Shading is flat Lambert with one
// directional light plus ambient, lit from whichever side faces the camera.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rlrun/frame.hpp"

namespace rlrun {

// OpenGL-style camera matrices (gluLookAt / gluPerspective).
Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                        const Eigen::Vector3f& up);
Eigen::Matrix4f perspective(float fov_y_radians, float aspect, float near, float far);

class Rasterizer {
 public:
  // Draws into `frame`, which must outlive the rasterizer; the depth buffer has its size.
  explicit Rasterizer(Frame& frame);

  void set_camera(const Eigen::Matrix4f& view, const Eigen::Matrix4f& projection);
  // `towards_light` need not be normalised; ambient in [0, 1] is the unlit brightness.
  void set_light(const Eigen::Vector3f& towards_light, float ambient = 0.3f);

  // Fills the frame with `background` and resets the depth buffer.
  void clear(Rgb background);
  // Resets the depth buffer only (draw a Cairo background first, then 3D on top).
  void clear_depth();

  // One triangle in world coordinates, flat shaded.
  void triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                Rgb color);
  // A triangle mesh: `model` places the vertices in the world.
  void mesh(std::span<const Eigen::Vector3f> vertices,
            std::span<const std::array<int, 3>> triangles, const Eigen::Matrix4f& model, Rgb color);

  // Depth of the nearest surface drawn at pixel (x, y), in [0, 1] (0 = near plane);
  // +infinity where nothing was drawn.
  float depth(int x, int y) const { return depth_[static_cast<size_t>(y) * width_ + x]; }
  // Pixels written since the last clear (for tests and statistics).
  int64_t pixels_written() const { return pixels_written_; }

 private:
  struct ScreenVertex {
    float x, y, z;  // pixels (y down) and depth in [0, 1]
  };
  void raster(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, uint32_t color);
  ScreenVertex to_screen(const Eigen::Vector4f& clip) const;

  Frame& frame_;
  int width_, height_;
  std::vector<float> depth_;
  Eigen::Matrix4f view_ = Eigen::Matrix4f::Identity();
  Eigen::Matrix4f view_projection_ = Eigen::Matrix4f::Identity();
  Eigen::Vector3f eye_ = Eigen::Vector3f::Zero();
  Eigen::Vector3f towards_light_ = Eigen::Vector3f(0, 0, 1);
  float ambient_ = 0.3f;
  int64_t pixels_written_ = 0;
};

}  // namespace rlrun
