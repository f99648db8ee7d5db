#pragma once
// Turns a Discrete / MultiDiscrete / MultiBinary observation into the Box the algorithms
// take, exactly as SB3 feeds such observations to its networks
// (stable_baselines3/common/preprocessing.py preprocess_obs): Discrete(n) becomes a one-hot
// vector of n floats, MultiDiscrete(nvec) the concatenated one-hots of its entries,
// MultiBinary(n) its n bits as floats. The result is Box(0, 1, (total,)). Used as
// `wrappers: [{id: OneHotObservation}]`, e.g. for GridWorld-v0.
#include <vector>

#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class OneHotObservation : public Wrapper {
 public:
  struct Config {
    template <class V>
    void visit(V&) {}
  };
  // Throws std::invalid_argument when the inner observation space is a Box.
  OneHotObservation(EnvPtr inner, const Config& config);
  explicit OneHotObservation(EnvPtr inner) : OneHotObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // Decodes the one-hot observation back to the inner env's and lets it draw that.
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

 private:
  void encode(std::span<float> obs) const;

  Space space_;
  std::vector<int64_t> sizes_;   // one-hot width of each inner entry (1 for MultiBinary bits)
  std::vector<int64_t> starts_;  // value of each entry's first slot (Discrete's start)
  std::vector<float> inner_obs_;
};

}  // namespace rlrun
