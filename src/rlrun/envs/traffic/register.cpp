// Traffic-signal control on the real SUMO; episodes end by num_seconds. The baseline is a
// fixed-time plan (eval --baseline fixed-time, record --policy fixed-time).
#include <cmath>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/traffic/fixed_time_policy.hpp"
#include "rlrun/envs/traffic/traffic_signal.hpp"

namespace rlrun::envs {

void register_traffic(EnvEntries& out) {
  EnvEntry entry = make_env_entry<TrafficSignal>(
      "TrafficSignal-v0",
      "one traffic light at a 4-arm intersection in SUMO (TrafficNetwork-v0's single-intersection "
      "case); Discrete(4): N, S, E or W green",
      0);
  entry.policies.push_back(
      {"fixed-time", "N -> S -> E -> W, green_time seconds each (--green-time, default 30)",
       [](Env& env, const PolicyOptions& options) {
         const auto it = options.settings.find("green_time");
         const double green = it == options.settings.end() ? 30.0 : it->second;
         if (!(green >= 1 && green <= 86400 && std::floor(green) == green))
           throw UsageError("--green-time must be a whole number of seconds in [1, 86400]");
         return fixed_time_actions(env, static_cast<int>(green));
       }});
  entry.metrics = {"avg_waiting_time", "avg_travel_time", "throughput", "total_queue_length"};
  out.push_back(std::move(entry));
}

}  // namespace rlrun::envs
