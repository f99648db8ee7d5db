#include "rlrun/envs/mujoco/model_layout.hpp"

#include "rlrun/core/errors.hpp"

namespace rlrun::mujoco {

namespace {

std::string describe(const ModelLayout& l) {
  return "nq=" + std::to_string(l.nq) + ", nv=" + std::to_string(l.nv) +
         ", nbody=" + std::to_string(l.nbody);
}

}  // namespace

void require_layout(const std::string& id, const std::string& path, const mjModel& model,
                    const ModelLayout& expected) {
  const ModelLayout actual{model.nq, model.nv, model.nbody};
  if (actual.nq == expected.nq && actual.nv == expected.nv && actual.nbody == expected.nbody)
    return;
  throw ConfigError(id + ": " + path + ": the model has " + describe(actual) + "; " + id +
                    "'s observation needs " + describe(expected) +
                    " (the joints and bodies of its shipped model)");
}

}  // namespace rlrun::mujoco
