#include "rlrun/runtime/env_factory.hpp"

#include <algorithm>
#include <chrono>

#include "rlrun/wrappers/monitor.hpp"
#include "rlrun/wrappers/observation_tap.hpp"
#include "rlrun/wrappers/time_limit.hpp"

namespace rlrun {

double unix_time_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

EnvPtr make_env(const EnvSpec& spec, const Registry& registry, const std::string& monitor_path,
                double t_start, bool tap_observations, bool append_monitor) {
  const EnvEntry& entry = registry.env(spec.id, spec.id_node);
  EnvPtr env = entry.make(spec.kwargs);
  const int limit = spec.section.max_episode_steps.value_or(entry.max_episode_steps);
  if (limit > 0) env = std::make_unique<TimeLimit>(std::move(env), limit);
  env = std::make_unique<Monitor>(std::move(env), monitor_path, t_start,
                                  std::vector<std::string>{"is_success"}, append_monitor);
  if (tap_observations) env = std::make_unique<ObservationTap>(std::move(env));
  for (const ConfigNode& w : spec.wrappers) {
    const WrapperEntry& wrapper = registry.wrapper(w.child("id").as_string(), w.child("id"));
    env = wrapper.make(std::move(env), w);
  }
  return adapt_action_space(std::move(env), spec, registry);
}

EnvPtr adapt_action_space(EnvPtr env, const EnvSpec& spec, const Registry& registry) {
  const auto& accepted = spec.accepted_action_spaces;
  const SpaceKind kind = env->action_space().kind();
  if (accepted.empty() || std::find(accepted.begin(), accepted.end(), kind) != accepted.end())
    return env;
  auto accepts = [&](SpaceKind k) { return std::find(accepted.begin(), accepted.end(), k) != accepted.end(); };
  std::string fix;
  if (kind == SpaceKind::kDiscrete && accepts(SpaceKind::kBox)) fix = "DiscreteAsBox";
  if (kind == SpaceKind::kBox && accepts(SpaceKind::kDiscrete)) fix = "BoxAsDiscrete";
  if (!fix.empty() && spec.section.auto_wrap) {
    const ConfigNode params = ConfigNode::from_yaml(YAML::Node(YAML::NodeType::Map), "auto_wrap");
    return registry.wrapper(fix, params).make(std::move(env), params);
  }
  std::string names;
  for (SpaceKind k : accepted) names += std::string(names.empty() ? "" : " or ") + (k == SpaceKind::kBox ? "Box" : k == SpaceKind::kDiscrete ? "Discrete" : k == SpaceKind::kMultiDiscrete ? "MultiDiscrete" : "MultiBinary");
  std::string message = spec.algorithm_id + " supports " + names + " actions, but " + spec.id +
                        " has " + env->action_space().describe();
  if (!fix.empty())
    message += ": add `wrappers: [{id: " + fix + "}]` to env, or set `env.auto_wrap: true`";
  spec.id_node.fail(message);
}

VecEnv make_vec_env(const EnvSpec& spec, const Registry& registry, int n_envs,
                    const std::string& monitor_dir, int tap_env, bool append_monitor) {
  std::vector<EnvPtr> envs;
  const double t_start = unix_time_now();
  for (int i = 0; i < n_envs; ++i) {
    const std::string path = monitor_dir.empty() ? "" : monitor_dir + "/" + monitor_file_name(i);
    envs.push_back(make_env(spec, registry, path, t_start, i == tap_env, append_monitor));
  }
  return VecEnv(std::move(envs));
}

std::string monitor_file_name(int i) { return std::to_string(i) + ".monitor.csv"; }

}  // namespace rlrun
