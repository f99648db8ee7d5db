#pragma once
// Turns a Discrete / MultiDiscrete / MultiBinary observation into a Box, exactly as SB3 feeds
// such observations to its networks (stable_baselines3/common/preprocessing.py preprocess_obs;
// env/observation_encoder.hpp does the encoding): Discrete(n) becomes a one-hot vector of n
// floats, MultiDiscrete(nvec) the concatenated one-hots of its entries, MultiBinary(n) its n
// bits as floats. The result is Box(0, 1, (total,)). PPO and A2C encode such observations
// themselves; the wrapper is for the algorithms that take Box observations only, for wrappers
// that need a Box (FrameStack, NormalizeObservation), and for configs written before.
// Used as `wrappers: [{id: OneHotObservation}]`, e.g. for GridWorld-v0.
#include <vector>

#include "rlrun/env/observation_encoder.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/no_options.hpp"

namespace rlrun {

class OneHotObservation : public Wrapper {
 public:
  using Config = NoOptions;
  // Throws std::invalid_argument when the inner observation space is a Box or a Dict.
  OneHotObservation(EnvPtr inner, const Config& config);
  explicit OneHotObservation(EnvPtr inner) : OneHotObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // Decodes the one-hot observation back to the inner env's and lets it draw that.
  bool render_observation(std::span<const float> obs, Frame& frame) const override;
  std::string export_observation(PolicyGraph& graph, const std::string& obs) const override {
    return encoder_.export_to(graph, obs);
  }
  std::string export_action(PolicyGraph& /*graph*/, const std::string& action) const override {
    return action;
  }

 private:
  void encode(std::span<float> obs) const;

  Space space_;
  ObservationEncoder encoder_;
  std::vector<float> inner_obs_;
};

}  // namespace rlrun
