#include "rlrun/runtime/experiment/env_factory.hpp"

#include <algorithm>
#include <chrono>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/spaces_only_env.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/wrappers/monitor.hpp"
#include "rlrun/wrappers/observation_tap.hpp"
#include "rlrun/wrappers/time_limit.hpp"
#include "rlrun/wrappers/vec_normalize.hpp"

namespace rlrun {

double unix_time_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

EnvContext env_context(const EnvSectionConfig& section) {
  return EnvContext{section.python.value, section.startup_timeout, section.opponent,
                    section.learner_side, section.agent_indicator};
}

namespace {

[[noreturn]] void fail_at_env(const EnvSpec& spec, const std::string& message) {
  throw ConfigError(spec.where + ": env.id: " + message);
}

const EnvEntry& env_entry(const EnvSpec& spec, const Registry& registry) {
  std::string why;  // a malformed family id, or an env this build left out
  const EnvEntry* entry = registry.find_env(spec.id, &why);
  if (!entry) fail_at_env(spec, why.empty() ? "unknown environment '" + spec.id + "'" : why);
  return *entry;
}

// The registered env alone (a Python env's worker starts here and answers while the caller
// goes on: make_vec_env starts every copy before it wraps any).
EnvPtr make_registered_env(const EnvSpec& spec, const Registry& registry) {
  const EnvEntry& entry = env_entry(spec, registry);
  return entry.build(spec.kwargs.empty() ? entry.parse(ConfigNode()) : spec.kwargs,
                     env_context(spec.section));
}

// `n` registered envs, all started before any is asked its spaces (a Python env's worker
// answers its handshake then, so the workers start in parallel). An env that cannot be built
// (a module that does not import, an __init__ that raises or hangs, a space rlrun cannot learn
// on) is the experiment's problem, said at its env.id, as parsing says one whose entry refuses
// its kwargs.
std::vector<EnvPtr> build_registered_envs(const EnvSpec& spec, const Registry& registry, int n) {
  std::vector<EnvPtr> envs;
  try {
    for (int i = 0; i < n; ++i) envs.push_back(make_registered_env(spec, registry));
    for (const EnvPtr& env : envs) (void)env->observation_space();
  } catch (const RuntimeFailure& e) {
    fail_at_env(spec, e.what());
  } catch (const std::invalid_argument& e) {
    fail_at_env(spec, e.what());
  }
  return envs;
}

// TimeLimit, Monitor, the user's wrappers and the action adapter around a registered env.
// `entry` is null only under an env known by its spaces (make_spaces_only_env) whose id this
// build does not register: a model loaded for predict or export.
EnvPtr wrap_env(EnvPtr env, const EnvSpec& spec, const EnvEntry* entry, const Registry& registry,
                const std::string& monitor_path, double t_start, bool tap_observations,
                bool append_monitor) {
  const int limit = spec.section.max_episode_steps.value_or(entry ? entry->max_episode_steps : 0);
  if (limit > 0) env = std::make_unique<TimeLimit>(std::move(env), limit);
  std::vector<std::string> keywords =
      entry ? episode_info_keywords(spec, registry, *env)
            : spec.section.info_keywords.value_or(std::vector<std::string>{});
  env = std::make_unique<Monitor>(std::move(env), monitor_path, t_start, std::move(keywords),
                                  append_monitor);
  // Several agents: TimeLimit and Monitor know how to step them; other wrappers not yet.
  if (env->num_agents() > 1 &&
      (tap_observations || !spec.wrappers.empty() || spec.section.normalize.enabled))
    fail_at_env(spec, spec.id + " has " + std::to_string(env->num_agents()) +
                          " agents; env.wrappers, env.normalize and obs_log do not support "
                          "multi-agent envs yet");
  if (tap_observations) env = std::make_unique<ObservationTap>(std::move(env));
  for (const WrapperSpec& w : spec.wrappers) {
    const WrapperEntry* wrapper = registry.find_wrapper(w.id);
    if (!wrapper) fail_at_env(spec, "unknown wrapper '" + w.id + "'");
    env = wrapper->make(std::move(env), w.params);
  }
  env = adapt_action_space(std::move(env), spec, registry);
  // Outermost, where SB3's VecNormalize wraps the VecEnv.
  try {
    return add_normalization(std::move(env), spec.section.normalize, spec.normalize_gamma());
  } catch (const std::invalid_argument& e) {
    fail_at_env(spec, std::string("env.normalize: ") + e.what());
  }
}

}  // namespace

EnvPtr make_env(const EnvSpec& spec, const Registry& registry, const std::string& monitor_path,
                double t_start, bool tap_observations, bool append_monitor) {
  return wrap_env(std::move(build_registered_envs(spec, registry, 1).front()), spec,
                  &env_entry(spec, registry), registry, monitor_path, t_start, tap_observations,
                  append_monitor);
}

std::optional<EnvSpaces> declared_env_spaces(const EnvSpec& spec, const Registry& registry) {
  const EnvEntry& entry = env_entry(spec, registry);
  if (!entry.spaces) return std::nullopt;
  return entry.spaces(spec.kwargs.empty() ? entry.parse(ConfigNode()) : spec.kwargs);
}

EnvPtr make_spaces_only_env(const EnvSpec& spec, const Registry& registry, const EnvSpaces& env) {
  return wrap_env(std::make_unique<SpacesOnlyEnv>(spec.id, env), spec, registry.find_env(spec.id),
                  registry, "", 0.0, false, false);
}

EnvPtr adapt_action_space(EnvPtr env, const EnvSpec& spec, const Registry& registry) {
  const auto& accepted = spec.accepted_action_spaces;
  const SpaceKind kind = env->action_space().kind();
  if (accepted.empty() || std::find(accepted.begin(), accepted.end(), kind) != accepted.end())
    return env;
  auto accepts = [&](SpaceKind k) {
    return std::find(accepted.begin(), accepted.end(), k) != accepted.end();
  };
  std::string fix;
  if (kind == SpaceKind::kDiscrete && accepts(SpaceKind::kBox)) fix = "DiscreteAsBox";
  if (kind == SpaceKind::kBox && accepts(SpaceKind::kDiscrete)) fix = "BoxAsDiscrete";
  if (!fix.empty() && spec.section.auto_wrap) {
    const WrapperEntry* wrapper = registry.find_wrapper(fix);
    if (wrapper) return wrapper->make(std::move(env), wrapper->parse(ConfigNode()));
  }
  std::string names;
  for (SpaceKind k : accepted)
    names += std::string(names.empty() ? "" : " or ") + (k == SpaceKind::kBox        ? "Box"
                                                         : k == SpaceKind::kDiscrete ? "Discrete"
                                                         : k == SpaceKind::kMultiDiscrete
                                                             ? "MultiDiscrete"
                                                             : "MultiBinary");
  std::string message = spec.algorithm_id + " supports " + names + " actions, but " + spec.id +
                        " has " + env->action_space().describe();
  if (!fix.empty())
    message += ": add `wrappers: [{id: " + fix + "}]` to env, or set `env.auto_wrap: true`";
  fail_at_env(spec, message);
}

VecEnv make_vec_env(const EnvSpec& spec, const Registry& registry, int n_envs,
                    const std::string& monitor_dir, int tap_env, bool append_monitor) {
  const double t_start = unix_time_now();
  std::vector<EnvPtr> envs = build_registered_envs(spec, registry, n_envs);
  for (int i = 0; i < n_envs; ++i) {
    const std::string path = monitor_dir.empty() ? "" : monitor_dir + "/" + monitor_file_name(i);
    envs[i] = wrap_env(std::move(envs[i]), spec, &env_entry(spec, registry), registry, path,
                       t_start, i == tap_env, append_monitor);
  }
  VecEnv vec(std::move(envs));
  install_batch_normalization(vec, spec.section.normalize);
  // Copies share nothing when the env says so and no wrapper shares state across them while
  // they step: normalisation statistics are shared (runtime/experiment/env_statistics.hpp) and
  // the observation tap feeds one log. env.normalize's wrappers are batched: the VecEnv's step
  // hook updates their statistics after every copy stepped, on the calling thread, so they
  // keep the copies independent (as SB3's VecNormalize sits above its VecEnv). The wrappers of
  // env.wrappers are otherwise per copy.
  const std::vector<ModelStatistics*> statistics = model_statistics(vec.env(0));
  const bool steps_update_statistics =
      std::any_of(statistics.begin(), statistics.end(),
                  [](const ModelStatistics* s) { return s->steps_update_statistics(); });
  vec.set_independent_copies(env_entry(spec, registry).independent_copies &&
                             !steps_update_statistics && tap_env < 0);
  return vec;
}

std::vector<std::string> episode_info_keywords(const EnvSpec& spec, const Registry& registry,
                                               const Env& env) {
  if (spec.section.info_keywords) return *spec.section.info_keywords;
  std::vector<std::string> keywords;
  if (env.info().find("is_success") >= 0) keywords.push_back("is_success");
  for (const std::string& key : env_entry(spec, registry).metrics)
    if (std::find(keywords.begin(), keywords.end(), key) == keywords.end()) keywords.push_back(key);
  return keywords;
}

std::string monitor_file_name(int i) { return std::to_string(i) + ".monitor.csv"; }

}  // namespace rlrun
