#pragma once
// The state of a top-down racing env (CarRacing-v3), as Gymnasium's CarRacing exposes it to
// Python (gymnasium/envs/box2d/car_racing.py: env.unwrapped.track, .car.hull, .car.wheels,
// .reward, .tile_visited_count, .t), plus what makes a transition checkable against
// Gymnasium's on the same track: read the track, set it for the next reset, read the car.
// A seed need not give Gymnasium's track (the RNGs differ, docs/box2d.md), a track set here
// does. The Python package offers this as env.unwrapped.track / .set_track / .car (python/,
// docs/car_racing.md); race_track_state_of finds it through wrappers.
#include <array>
#include <span>
#include <vector>

#include "rlrun/env.hpp"

namespace rlrun {

// One point of the track centre line: Gymnasium's (alpha, beta, x, y) tuple. alpha is the
// polar angle of the point, beta the road's heading (the car's angle at the start), x and y
// world units.
struct TrackPoint {
  double alpha = 0, beta = 0, x = 0, y = 0;
};

// Box2D's view of one body (world units, radians, SI per second).
struct RigidBodyState {
  std::array<double, 2> position{}, linear_velocity{};
  double angle = 0, angular_velocity = 0;
};

// car_dynamics.py's per-wheel controls and state.
struct WheelState {
  RigidBodyState body;
  double gas = 0, brake = 0, steer = 0;  // last controls
  double omega = 0;                      // angular velocity of the wheel's rotation (rad/s)
  double phase = 0;                      // wheel rotation angle (rad)
  double joint_angle = 0;                // steering joint angle (rad)
  int tiles = 0;                         // road tiles the wheel touches (0: on grass)
};

struct CarState {
  RigidBodyState hull;
  std::array<WheelState, 4> wheels;  // front left, front right, rear left, rear right
};

class RaceTrackState {
 public:
  virtual ~RaceTrackState() = default;
  // The current episode's track (empty before the first reset).
  virtual std::span<const TrackPoint> track() const = 0;
  // The next reset() builds the road of `track` instead of generating one (once; resets after
  // it generate again). Throws std::invalid_argument for a track that cannot be a road.
  virtual void set_next_track(std::vector<TrackPoint> track) = 0;
  // Gymnasium's reset(options={"randomize": bool}) with domain_randomize: whether the next
  // reset draws new colours (the default) or keeps the current ones.
  virtual void set_next_randomize(bool randomize) = 0;
  // Throws std::logic_error before the first reset.
  virtual CarState car() const = 0;
  virtual double episode_reward() const = 0;  // Gymnasium's env.reward (tile rewards - 0.1/frame)
  virtual int tiles_visited() const = 0;      // env.tile_visited_count
  virtual double time() const = 0;            // env.t, seconds since reset
};

// The RaceTrackState under any wrappers, or nullptr when the env is no racing env.
inline RaceTrackState* race_track_state_of(Env& env) {
  return dynamic_cast<RaceTrackState*>(&env.unwrapped());
}

}  // namespace rlrun
