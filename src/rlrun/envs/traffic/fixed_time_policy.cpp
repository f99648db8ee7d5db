#include "rlrun/envs/traffic/fixed_time_policy.hpp"

#include <memory>
#include <stdexcept>

#include "rlrun/core/errors.hpp"

#include "rlrun/envs/traffic/traffic_signal.hpp"

namespace rlrun {

FixedTimePolicy::FixedTimePolicy(int green_time, int delta_time) {
  if (green_time <= 0 || delta_time <= 0)
    throw std::invalid_argument("fixed-time plan: green time and delta_time must be positive");
  decisions_per_green_ = (green_time + delta_time - 1) / delta_time;
}

int FixedTimePolicy::next_action(bool episode_start) {
  if (episode_start) decision_ = 0;
  static constexpr int kCycle[] = {traffic::kNorth, traffic::kSouth, traffic::kEast,
                                   traffic::kWest};
  return kCycle[(decision_++ / decisions_per_green_) % 4];
}

std::function<void(const Eigen::MatrixXf&, Eigen::MatrixXf&)> fixed_time_actions(Env& env,
                                                                                 int green_time) {
  auto* traffic = dynamic_cast<TrafficSignal*>(&env.unwrapped());
  if (!traffic)
    throw UsageError("the fixed-time plan is the traffic-signal baseline; this env is " +
                     env.unwrapped().id());
  auto plan = std::make_shared<FixedTimePolicy>(green_time, traffic->config().delta_time);
  return [plan, traffic](const Eigen::MatrixXf&, Eigen::MatrixXf& action) {
    action.resize(1, 1);
    // reset() simulates the first second: a new episode is at 1 s.
    action(0, 0) = static_cast<float>(plan->next_action(traffic->sim_time() <= 1.0));
  };
}

}  // namespace rlrun
