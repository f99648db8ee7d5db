#include "rlrun/envs/traffic/fixed_time_policy.hpp"

#include <stdexcept>

#include "rlrun/envs/traffic/traffic_signal.hpp"

namespace rlrun {

FixedTimePolicy::FixedTimePolicy(int green_time, int delta_time) {
  if (green_time <= 0 || delta_time <= 0)
    throw std::invalid_argument("fixed-time plan: green time and delta_time must be positive");
  decisions_per_green_ = (green_time + delta_time - 1) / delta_time;
}

int FixedTimePolicy::next_action(bool episode_start) {
  if (episode_start) decision_ = 0;
  static constexpr int kCycle[] = {TrafficSignal::kNorth, TrafficSignal::kSouth,
                                   TrafficSignal::kEast, TrafficSignal::kWest};
  return kCycle[(decision_++ / decisions_per_green_) % 4];
}

}  // namespace rlrun
