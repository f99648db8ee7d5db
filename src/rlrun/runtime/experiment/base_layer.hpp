#pragma once
// Slipping a layer between an env stack and the env it wraps (below TimeLimit, Monitor and
// the user's wrappers), where observations and actions are the env's own: what a Gymnasium
// user of the bare env sees. `rlrun eval --trajectory` records there
// (runtime/run/trajectory_tap.hpp); a model's Python predict() feeds the stack from there
// (runtime/io/model_policy.hpp).
#include <functional>
#include <stdexcept>

#include "rlrun/env/wrapper.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"

namespace rlrun {

// `wrap` receives the env (the registered env, with the wrappers that belong to its id:
// Wrapper::belongs_to_env) and returns the layer that replaces it (owning it). Throws
// std::logic_error for a stack without wrappers (make_env always adds a Monitor).
template <class Layer>
Layer& insert_base_layer(Env& stack, const std::function<std::unique_ptr<Layer>(EnvPtr)>& wrap) {
  const std::vector<Wrapper*> chain = wrapper_chain(stack);
  size_t above_env = chain.size();  // the wrappers from the outermost down, before the env's own
  for (size_t k = 0; k < chain.size(); ++k)
    if (chain[k]->belongs_to_env()) {
      above_env = k;
      break;
    }
  if (above_env == 0) throw std::logic_error(stack.id() + ": the env has no wrapper stack");
  Wrapper* innermost = chain[above_env - 1];
  std::unique_ptr<Layer> layer = wrap(innermost->exchange_inner(nullptr));
  Layer& out = *layer;
  innermost->exchange_inner(std::move(layer));
  return out;
}

}  // namespace rlrun
