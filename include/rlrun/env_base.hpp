#pragma once
// A convenience base for envs that keep their spaces and info as members, the way a
// gymnasium.Env sets self.observation_space and self.action_space in __init__:
//
//   class GoLeft : public rlrun::EnvBase {
//    public:
//     GoLeft() {
//       observation_space_ = rlrun::Space::box(0.0f, 10.0f, {1});
//       action_space_ = rlrun::Space::discrete(2);
//     }
//     void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
//       seeding_.on_reset(seed);                   // super().reset(seed=seed)
//       ...
//     }
//     rlrun::StepResult step(std::span<const float> action, std::span<float> obs) override;
//   };
//
// Everything else is rlrun::Env's (rlrun/env.hpp), including the optional render() and
// write_state() / read_state(). id() is the id the env was registered with (plugins: set by
// rlrun when it builds the env).
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"

namespace rlrun {

class EnvBase : public Env {
 public:
  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return id_; }

 protected:
  Space observation_space_;  // set in the constructor (Gymnasium: self.observation_space)
  Space action_space_;       // set in the constructor (Gymnasium: self.action_space)
  Info info_;                // declare keys in the constructor, set values in reset/step
  EnvSeeding seeding_;       // the env's random stream (Gymnasium: self.np_random)
  std::string id_;           // the registered id, when the env knows it
};

}  // namespace rlrun
