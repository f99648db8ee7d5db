#pragma once
// Camera observations for the gripper tasks (issue: learning to grasp from pixels): the scene
// of gripper_scene_render.hpp drawn headless by rlrun's rasterizer at image_size x image_size,
// from a fixed camera (the render's, front-right and above) or a wrist camera (on the palm,
// behind the fingers, looking down past them, so it moves with the gripper as on a robot arm).
// obs_type picks what the agent sees:
//   state   the env's state vector (the default; unchanged)
//   pixels  Box(0, 255, (image_size, image_size, 3), uint8): SB3's image space (CnnPolicy)
//   both    Dict{pixels: that image, state: the state vector} (MultiInputPolicy's
//           CombinedExtractor: a NatureCNN for the image, the vector flattened)
#include <memory>
#include <span>
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/envs/gripper/gripper_scene_render.hpp"
#include "rlrun/envs/gripper/gripper_world.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/rasterizer.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// The kwargs every gripper task shares for its camera.
struct GripperCameraConfig {
  std::string obs_type = "state";  // state | pixels | both
  std::string camera = "fixed";    // fixed | wrist
  int image_size = 84;             // pixels per side

  template <class V>
  void visit(V& v) {
    v("obs_type", obs_type,
      "state (the vector), pixels (a uint8 camera image, CnnPolicy) or both (Dict pixels + "
      "state, MultiInputPolicy)",
      OneOf{{"state", "pixels", "both"}});
    v("camera", camera, "fixed (front-right, above the table) or wrist (on the palm)",
      OneOf{{"fixed", "wrist"}});
    v("image_size", image_size, "camera image side in pixels", in_range(16, 512));
  }
};

// The camera of a wrist view for the gripper's current pose.
GripperCamera wrist_camera(const GripperWorld& world);

class GripperCameraObservation {
 public:
  // Throws std::invalid_argument for an unknown obs_type or camera (naming the env).
  GripperCameraObservation(const GripperCameraConfig& config, const std::string& env_id);

  bool uses_pixels() const { return pixels_; }
  bool uses_state() const { return state_; }
  // The observation space around the env's state space.
  Space space(const Space& state_space) const;
  // Where the state vector goes in an observation (the whole of it for `state`; the `state`
  // key's part for `both`); empty for `pixels`.
  std::span<float> state_part(std::span<float> obs, const Space& space) const;
  // Draws the camera image into its part of `obs` (0-255 values, row-major H x W x 3).
  void write_pixels(const GripperWorld& world, Rgb cube_color, std::span<float> obs,
                    const Space& space);
  // The image alone: Space::image({image_size, image_size, 3}), its number of floats, and
  // drawing it into `out`.
  Space image_space() const;
  size_t image_floats() const {
    return static_cast<size_t>(config_.image_size) * config_.image_size * 3;
  }
  void write_image(const GripperWorld& world, Rgb cube_color, std::span<float> out);

 private:
  std::span<float> pixels_part(std::span<float> obs, const Space& space) const;

  GripperCameraConfig config_;
  bool pixels_ = false, state_ = true, wrist_ = false;
  // Made at the first image and kept: drawing allocates nothing per step.
  std::unique_ptr<Frame> frame_;
  std::unique_ptr<Rasterizer> raster_;  // draws into *frame_
};

}  // namespace rlrun
