#include "rlrun/envs/mujoco/model_shape.hpp"

#include "rlrun/core/errors.hpp"

namespace rlrun::mujoco {

namespace {

std::string counts(const ModelShape& shape) {
  return "nq=" + std::to_string(shape.nq) + ", nv=" + std::to_string(shape.nv) +
         ", nu=" + std::to_string(shape.nu) +
         (shape.nbody >= 0 ? ", nbody=" + std::to_string(shape.nbody) : std::string());
}

}  // namespace

void require_shape(const mjModel& model, const ModelShape& expected, const std::string& id,
                   const std::string& path) {
  const ModelShape actual{model.nq, model.nv, model.nu, expected.nbody >= 0 ? model.nbody : -1};
  if (actual.nq == expected.nq && actual.nv == expected.nv && actual.nu == expected.nu &&
      actual.nbody == expected.nbody)
    return;
  throw ConfigError(path + ": " + id + " needs a model with " + counts(expected) +
                    " (its own model's: the observation is laid out for those); this one has " +
                    counts(actual));
}

}  // namespace rlrun::mujoco
