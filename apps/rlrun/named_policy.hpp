#pragma once
// The policies that need no model file, by name, for `eval --policy`, `eval --baseline` and
// `record --policy`: `random` (uniform actions from the action space, their own stream seeded
// from the options' seed) for every env, and the baselines an env folder registers with its
// env (env/env_entry.hpp: e.g. the traffic task's `fixed-time`, the grasp task's `scripted`).
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/env/policy.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::cli {

struct NamedPolicy {
  PolicyFn act;
  std::string label;  // for overlays and summaries, e.g. "fixed-time 30 s"
};

// Throws UsageError naming the env's policies when `name` is not one of them, or when the
// policy does not fit `env`.
NamedPolicy named_policy(const std::string& name, Env& env, const Registry& registry,
                         const PolicyOptions& options);

}  // namespace rlrun::cli
