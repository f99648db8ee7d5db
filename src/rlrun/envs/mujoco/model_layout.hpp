#pragma once
// The sizes of a MuJoCo model that a task's observation is made of (qpos, qvel, and the per-body
// arrays cinert, cvel, cfrc_ext). Gymnasium fixes each task's observation length for its shipped
// model; a model given as `xml_file` must have the same sizes, or its observation would not fit
// the space: rlrun refuses it when the env is built.
#include <mujoco/mujoco.h>

#include <string>

namespace rlrun::mujoco {

struct ModelLayout {
  int nq = 0;     // generalised positions
  int nv = 0;     // generalised velocities
  int nbody = 0;  // bodies, the world included
};

// Throws ConfigError "<id>: <path>: the model has nq=..., nv=..., nbody=...; <id> needs ..."
// when `model` (compiled from `path`) differs from `expected`.
void require_layout(const std::string& id, const std::string& path, const mjModel& model,
                    const ModelLayout& expected);

}  // namespace rlrun::mujoco
