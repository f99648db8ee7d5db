#pragma once
// TransformReward: reward' = clip(scale * reward + offset, clip_min, clip_max), a
// configurable form of gymnasium/wrappers/transform_reward.py's TransformReward / ClipReward.
// E.g. `{id: TransformReward, scale: 0.01}` for large rewards, `{id: TransformReward,
// clip_min: -1, clip_max: 1}` for clipping, `{id: TransformReward, sign: true}` for SB3's
// ClipRewardEnv (atari_wrappers.py: np.sign(reward), so 0.3 becomes 1 where clipping keeps 0.3). Applied after the Monitor, so logged
// episode returns stay the env's own.
#include <optional>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class TransformReward : public Wrapper, public SplitStep {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  struct Config {
    bool sign = false;               // replaces the reward by its sign (-1, 0, 1) before all else
    double scale = 1.0;              // multiplies the reward first
    double offset = 0.0;             // then is added
    std::optional<double> clip_min;  // then the result is clipped from below (null: no bound)
    std::optional<double> clip_max;  // and from above (null: no bound)
    template <class V>
    void visit(V& v) {
      v("sign", sign, "replace the reward by its sign -1, 0 or 1 first (SB3 ClipRewardEnv)");
      v("scale", scale, "factor applied to the reward (after sign)");
      v("offset", offset, "added after scaling");
      v("clip_min", clip_min, "lower clip of the result (null = none)");
      v("clip_max", clip_max, "upper clip of the result (null = none)");
    }
  };
  // Throws std::invalid_argument when clip_min > clip_max.
  TransformReward(EnvPtr inner, const Config& config);
  explicit TransformReward(EnvPtr inner) : TransformReward(std::move(inner), Config()) {}

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // The two halves of step() (env/split_step.hpp): forwarded, then the reward transformed.
  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(action);
  }
  StepResult finish_step(std::span<float> obs) override {
    return transform(asynchronous_steps(*inner_)->finish_step(obs));
  }

 private:
  StepResult transform(StepResult result) const;
  Config config_;
};

}  // namespace rlrun
