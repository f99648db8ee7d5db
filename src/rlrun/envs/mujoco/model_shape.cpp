#include "rlrun/envs/mujoco/model_shape.hpp"

#include "rlrun/core/errors.hpp"

namespace rlrun::mujoco {

namespace {

std::string counts(int nq, int nv, int nu) {
  return "nq=" + std::to_string(nq) + ", nv=" + std::to_string(nv) + ", nu=" + std::to_string(nu);
}

}  // namespace

void require_shape(const mjModel& model, const ModelShape& expected, const std::string& id,
                   const std::string& path) {
  if (model.nq == expected.nq && model.nv == expected.nv && model.nu == expected.nu) return;
  throw ConfigError(path + ": " + id + " needs a model with " +
                    counts(expected.nq, expected.nv, expected.nu) +
                    " (its own model's: the observation is laid out for those); this one has " +
                    counts(model.nq, model.nv, model.nu));
}

}  // namespace rlrun::mujoco
