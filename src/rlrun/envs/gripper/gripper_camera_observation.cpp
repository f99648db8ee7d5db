#include "rlrun/envs/gripper/gripper_camera_observation.hpp"

#include <stdexcept>

namespace rlrun {

GripperCamera wrist_camera(const GripperWorld& world) {
  // Under the palm, between the fingers' roots, looking down and a little forward: the
  // fingers frame the view left and right, the table and the cube lie below.
  const Vec3 g = world.grasp_point();
  GripperCamera camera;
  camera.eye = {static_cast<float>(g[0]), static_cast<float>(g[1] - 0.01),
                static_cast<float>(g[2] + 0.05)};
  camera.target = {static_cast<float>(g[0]), static_cast<float>(g[1] + 0.03),
                   static_cast<float>(g[2] - 0.08)};
  camera.fov_y = 1.4f;
  camera.near = 0.01f;
  return camera;
}

GripperCameraObservation::GripperCameraObservation(const GripperCameraConfig& config,
                                                   const std::string& env_id)
    : config_(config) {
  if (config.obs_type == "pixels") {
    pixels_ = true, state_ = false;
  } else if (config.obs_type == "both") {
    pixels_ = true, state_ = true;
  } else if (config.obs_type != "state") {
    throw std::invalid_argument(env_id + ": obs_type is state, pixels or both, not '" +
                                config.obs_type + "'");
  }
  if (config.camera == "wrist")
    wrist_ = true;
  else if (config.camera != "fixed")
    throw std::invalid_argument(env_id + ": camera is fixed or wrist, not '" + config.camera + "'");
  if (config.image_size < 16 || config.image_size > 512)
    throw std::invalid_argument(env_id + ": image_size must lie in [16, 512]");
}

Space GripperCameraObservation::image_space() const {
  return Space::image({config_.image_size, config_.image_size, 3});
}

Space GripperCameraObservation::space(const Space& state_space) const {
  if (!pixels_) return state_space;
  Space image = image_space();
  if (!state_) return image;
  return Space::dict({{"pixels", std::move(image)}, {"state", state_space}});
}

std::span<float> GripperCameraObservation::state_part(std::span<float> obs,
                                                      const Space& space) const {
  if (!state_) return {};
  if (!pixels_) return obs;
  // Keys sorted: pixels (0), state (1).
  return obs.subspan(static_cast<size_t>(space.offset(1)));
}

std::span<float> GripperCameraObservation::pixels_part(std::span<float> obs,
                                                       const Space& space) const {
  if (!state_) return obs.first(image_floats());
  return obs.subspan(static_cast<size_t>(space.offset(0)), image_floats());
}

void GripperCameraObservation::write_pixels(const GripperWorld& world, Rgb cube_color,
                                            std::span<float> obs, const Space& space) {
  if (pixels_) write_image(world, cube_color, pixels_part(obs, space));
}

void GripperCameraObservation::write_image(const GripperWorld& world, Rgb cube_color,
                                           std::span<float> out) {
  if (!frame_) {
    frame_ = std::make_unique<Frame>(config_.image_size, config_.image_size);
    raster_ = std::make_unique<Rasterizer>(*frame_);
  }
  draw_gripper_scene(*raster_, *frame_, world, wrist_ ? wrist_camera(world) : GripperCamera{},
                     cube_color);
  const uint32_t* pixels = frame_->pixels();
  const int size = config_.image_size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const uint32_t p = pixels[static_cast<size_t>(y) * frame_->stride_pixels() + x];
      float* rgb = out.data() + (static_cast<size_t>(y) * size + x) * 3;
      rgb[0] = static_cast<float>((p >> 16) & 0xff);
      rgb[1] = static_cast<float>((p >> 8) & 0xff);
      rgb[2] = static_cast<float>(p & 0xff);
    }
}

}  // namespace rlrun
