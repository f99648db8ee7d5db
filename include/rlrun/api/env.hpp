#pragma once
// The environment base class for plugins: the C++ counterpart of subclassing gymnasium.Env.
//
//   class GoLeft : public rlrun::api::Env {
//    public:
//     GoLeft() {                                   // __init__
//       observation_space_ = Space::box(0.0f, 10.0f, {1});
//       action_space_ = Space::discrete(2);
//     }
//     void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
//       seed_rng(seed);                            // super().reset(seed=seed)
//       ...; obs[0] = position;
//     }
//     StepResult step(std::span<const float> action, std::span<float> obs) override {...}
//   };
//
// Semantics are Gymnasium's (gymnasium/core.py): reset(seed) reseeds the env's random
// generator, reset() without a seed continues its stream; step() returns terminated (a true
// end of the task: rlrun never bootstraps from it) and truncated (cut short, e.g. by a time
// limit: bootstrapped). Prefer registering a time limit (Registrar::add_env) over truncating
// yourself. Observations and actions are flat float vectors laid out as the spaces say; a
// Discrete action is one float holding the integer. Throw std::exception subclasses on
// invalid input: rlrun reports them with the env's id.
#include <cstdint>
#include <optional>
#include <random>
#include <span>

#include "rlrun/api/info.hpp"
#include "rlrun/api/space.hpp"

namespace rlrun::api {

struct StepResult {
  double reward = 0.0;
  bool terminated = false;
  bool truncated = false;
};

class Env {
 public:
  virtual ~Env() = default;

  // Writes the first observation of a new episode into `obs` (observation_space().flat_dim()
  // floats) and sets info(). Call seed_rng(seed) first.
  virtual void reset(std::optional<uint64_t> seed, std::span<float> obs) = 0;
  // Applies `action` (action_space().flat_dim() floats), writes the next observation, sets
  // info() and returns the reward and the end-of-episode flags.
  virtual StepResult step(std::span<const float> action, std::span<float> obs) = 0;

  const Space& observation_space() const { return observation_space_; }
  const Space& action_space() const { return action_space_; }
  const Info& info() const { return info_; }

 protected:
  // Gymnasium's `super().reset(seed=seed)`: a seed reseeds rng_; no seed keeps its stream,
  // except that the first reset without any seed seeds from std::random_device.
  void seed_rng(std::optional<uint64_t> seed) {
    if (seed) {
      rng_.seed(*seed);
      seeded_ = true;
    } else if (!seeded_) {
      std::random_device device;
      rng_.seed((static_cast<uint64_t>(device()) << 32) ^ device());
      seeded_ = true;
    }
  }
  // Uniform double in [low, high) from rng_ (53 random bits; the same on every platform,
  // unlike std::uniform_real_distribution).
  double uniform(double low, double high) {
    return low + (high - low) * (static_cast<double>(rng_() >> 11) * 0x1.0p-53);
  }
  // Uniform integer in [low, high) (numpy's Generator.integers), unbiased.
  int64_t integers(int64_t low, int64_t high) {
    const uint64_t range = static_cast<uint64_t>(high - low);
    if (range == 0) return low;
    const uint64_t limit = UINT64_MAX - UINT64_MAX % range;
    uint64_t x = rng_();
    while (x >= limit) x = rng_();
    return low + static_cast<int64_t>(x % range);
  }

  Space observation_space_;  // set in the constructor (Gymnasium: self.observation_space)
  Space action_space_;       // set in the constructor (Gymnasium: self.action_space)
  Info info_;                // declare keys in the constructor, set values in reset/step
  std::mt19937_64 rng_;      // the env's own random generator (Gymnasium: self.np_random)

 private:
  bool seeded_ = false;
};

}  // namespace rlrun::api
