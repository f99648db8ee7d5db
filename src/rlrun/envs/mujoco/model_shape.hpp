#pragma once
// The joint and actuator counts a task's observation and reward are written for. A task's
// `xml_file` may name another model (the user's, or another shipped one: untrusted text may
// name shipped files, core/trusted_values.hpp); one with other counts would make the task read
// and write past its arrays, so the task refuses it when it is built.
#include <mujoco/mujoco.h>

#include <string>

namespace rlrun::mujoco {

struct ModelShape {
  int nq = 0;  // generalised positions (qpos)
  int nv = 0;  // generalised velocities (qvel)
  int nu = 0;  // actuators (the action's size)
  // Bodies, the world included, for tasks that observe per-body arrays (cinert, cvel, cfrc_ext:
  // Ant with contact forces, the Humanoids); -1 = not read by the task.
  int nbody = -1;
};

// Throws ConfigError "<path>: <id> needs a model with nq=.., nv=.., nu=..[, nbody=..] (its own
// model's); this one has ..." unless `model` has exactly `expected`'s counts.
void require_shape(const mjModel& model, const ModelShape& expected, const std::string& id,
                   const std::string& path);

}  // namespace rlrun::mujoco
