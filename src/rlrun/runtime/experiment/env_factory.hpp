#pragma once
// Builds the env stack for an experiment, in the order SB3's make_vec_env and gymnasium.make
// use: registered env -> TimeLimit (registered limit or override) -> Monitor (true episode
// returns, `<rank>.monitor.csv`) -> the user's wrappers in YAML order -> env.normalize (SB3's
// VecNormalize, outermost; batched over the copies of a VecEnv: wrappers/vec_normalize.hpp).
#include <optional>
#include <string>

#include "rlrun/env/env_entry.hpp"
#include "rlrun/env/env_spaces.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/experiment/env_spec.hpp"

namespace rlrun {

// `monitor_path` empty: statistics only, no file. `tap_observations` puts an ObservationTap
// (wrappers/observation_tap.hpp) right above the Monitor, for the obs_log callback.
// `append_monitor` continues the monitor file of a resumed run.
// What the env section (not the env's kwargs) decides about how the env is built: the Python
// interpreter and start-up time, a PettingZoo game's opponent and seat, the agent indicator.
EnvContext env_context(const EnvSectionConfig& section);

EnvPtr make_env(const EnvSpec& spec, const Registry& registry, const std::string& monitor_path,
                double t_start, bool tap_observations = false, bool append_monitor = false);

// The spaces of the env `spec` configures as its entry declares them (EnvEntry::spaces: no
// simulator or worker starts), or nullopt for an env whose spaces only a running worker knows.
// Throws ConfigError for an unknown id, std::invalid_argument for kwargs the env refuses.
std::optional<EnvSpaces> declared_env_spaces(const EnvSpec& spec, const Registry& registry);

// The stack make_env builds, over an env known by its spaces `env` (env/spaces_only_env.hpp):
// the spaces the agent sees, and a stack a model turns into a policy (predict, export). It
// cannot be stepped. The env's id need not be registered in this build.
EnvPtr make_spaces_only_env(const EnvSpec& spec, const Registry& registry, const EnvSpaces& env);

// Checks the env's action space against spec.accepted_action_spaces; with auto_wrap adds
// DiscreteAsBox or BoxAsDiscrete, otherwise a ConfigError names the wrapper that fixes it.
EnvPtr adapt_action_space(EnvPtr env, const EnvSpec& spec, const Registry& registry);

// n copies; env i writes `<monitor_dir>/<i>.monitor.csv` unless monitor_dir is empty. Env
// `tap_env` (if >= 0) gets an ObservationTap.
VecEnv make_vec_env(const EnvSpec& spec, const Registry& registry, int n_envs,
                    const std::string& monitor_dir, int tap_env = -1, bool append_monitor = false);

// The info keys Monitor reads at each episode's end (monitor.csv columns, `episode.<key>` info,
// rollout/<key> and eval/<key> means): env.info_keywords when set, else is_success when `env`
// declares it and the env's registered metrics (EnvEntry::metrics).
std::vector<std::string> episode_info_keywords(const EnvSpec& spec, const Registry& registry,
                                               const Env& env);

// `<i>.monitor.csv`: the monitor file of training env i, relative to the run directory.
std::string monitor_file_name(int i);

// Current Unix time in seconds (the Monitor's t_start).
double unix_time_now();

}  // namespace rlrun
