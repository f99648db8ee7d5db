#pragma once
// A task's DEFAULT_CAMERA_CONFIG (Gymnasium's *_v4.py): the free camera's settings when the model
// has no camera named "track" (MujocoRenderer sets the mjvCamera attributes named; unset ones keep
// MuJoCo's defaults). mujoco_renderer.hpp says how the camera is chosen.
#include <array>
#include <optional>

namespace rlrun::mujoco {

struct DefaultCamera {
  std::optional<int> trackbodyid = std::nullopt;
  std::optional<double> distance = std::nullopt;
  std::optional<std::array<double, 3>> lookat = std::nullopt;
  std::optional<double> elevation = std::nullopt;
  std::optional<double> azimuth = std::nullopt;
};

}  // namespace rlrun::mujoco
