// The built-in components: the envs every env folder registers (collected by CMake into
// builtin_env_entries(), build/generated/builtin_envs.cpp), and the wrappers and algorithms
// (runtime/components/policy_components.cpp) (docs/architecture.md).
#include "rlrun/runtime/components/builtins.hpp"

#include "rlrun/runtime/components/policy_components.hpp"
#include "rlrun/wrappers/add_render_observation.hpp"
#include "rlrun/wrappers/grayscale_observation.hpp"
#include "rlrun/wrappers/resize_observation.hpp"

namespace rlrun {

namespace {

Registry make_builtins() {
  Registry r;
  // Every env folder's register.cpp (src/rlrun/envs/*/register.cpp), collected by CMake.
  for (EnvEntry& entry : builtin_env_entries()) r.add(std::move(entry));
  add_builtin_wrappers(r);
  // The pixel wrappers draw (Cairo), so they stay out of policy_registry() and the deploy
  // library: a policy that reads rendered frames cannot be deployed without its renderer.
  r.add(make_wrapper_entry<AddRenderObservation>(
      "AddRenderObservation",
      "the env's rendered RGB frame as the observation, alone or beside it (Gymnasium)"));
  r.add(make_wrapper_entry<GrayscaleObservation>(
      "GrayscaleObservation",
      "RGB image observations to gray, Gymnasium's or OpenCV's weights (keep_dim)"));
  r.add(make_wrapper_entry<ResizeObservation>(
      "ResizeObservation", "image observations resized to [height, width], OpenCV's INTER_AREA"));
  add_builtin_algorithms(r);
  return r;
}

}  // namespace

Registry make_builtin_registry() { return make_builtins(); }

const Registry& builtin_registry() {
  static const Registry registry = make_builtins();
  return registry;
}

}  // namespace rlrun
