#pragma once
// MountainCar-v0: gymnasium/envs/classic_control/mountain_car.py (Gymnasium 1.0.0), Moore's
// (1990) under-powered car in a valley; 3 discrete actions (push left, none, push right).
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

// gymnasium.make("MountainCar-v0" or "MountainCarContinuous-v0", **kwargs) keyword arguments.
struct MountainCarConfig {
  // Minimum velocity at the goal position for the episode to terminate.
  double goal_velocity = 0.0;

  template <class V>
  void visit(V& v) {
    v("goal_velocity", goal_velocity, "minimum velocity at the goal for termination");
  }
};

// What MountainCar-v0 and MountainCarContinuous-v0 share (mountain_car.py and
// continuous_mountain_car.py): the track, the speed limit, the initial state
// np.array([np_random.uniform(low=-0.6, high=-0.4), 0]) (float64), and the observation, which
// is the state (position, velocity) in float32.
inline constexpr double kMountainCarMinPosition = -1.2;
inline constexpr double kMountainCarMaxPosition = 0.6;
inline constexpr double kMountainCarMaxSpeed = 0.07;
bool mountain_car_initial_state(NumpyRandom& np_random, std::span<double> state);
void mountain_car_observation(std::span<const double> state, std::span<float> obs);
Space mountain_car_observation_space();

// The state is position, velocity.
class MountainCar : public ClassicControlEnv {
 public:
  using Config = MountainCarConfig;
  static constexpr int kMaxEpisodeSteps = 200;  // registered TimeLimit (gymnasium/envs/__init__.py)

  explicit MountainCar(const Config& config = {});
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 private:
  Config config_;
};

}  // namespace rlrun
