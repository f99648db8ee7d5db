#pragma once
// NormalizeObservation: the observation half of SB3's VecNormalize
// (stable_baselines3/common/vec_env/vec_normalize.py):
//     obs' = clip((obs - mean) / sqrt(var + epsilon), -clip_obs, clip_obs)   (float64, then float32)
// with mean/var a RunningMeanStd updated, while training, with every observation reset() and
// step() return, except the last observation of an episode: as in VecNormalize, whose
// statistics see the auto-reset observation instead (the VecEnv resets this wrapper right
// after such a step, which adds the reset observation).
//
// One statistics object is shared by the n copies of a training VecEnv (see
// model_statistics.hpp), so the statistics after every VecEnv step equal VecNormalize's (up to
// rounding: n single-sample updates instead of one batch update). Difference from
// VecNormalize: within one VecEnv step, env i is normalised with statistics that already hold
// envs 0..i of that step (VecNormalize: all n), and a final observation with statistics
// before (VecNormalize: after) the reset observation was added. With n_envs = 1 the
// statistics and all other observations are bit-identical to SB3's.
// The observation space becomes Box(-clip_obs, clip_obs) of the same shape.
// `freeze_after: N` stops the updates once the statistics hold N observations (counted over
// every copy) and keeps them fixed for the rest of training, as setting Gymnasium's NormalizeObservation.update_running_mean = False (or
// SB3's VecNormalize.training = False) at that point would. RLtools' PPO does this: mean and
// std from one rollout of the initial policy, then frozen (configs/rltools/pendulum_ppo.yaml).
// The count is part of the statistics, so a resumed run freezes where the original did.
// A Dict observation is normalised key by key as VecNormalize does with `norm_obs_keys`: the
// listed keys (default: every Box key; SB3's default, all keys, fails on a non-Box key) each
// become Box(-clip_obs, clip_obs), the others pass unchanged. One RunningMeanStd holds the
// normalised keys' floats in sorted key order; it equals SB3's one-per-key statistics, which are
// updated with the same observations and so share one count.
// A threaded VecEnv must not step two copies sharing statistics at the same time.
//
// `env.normalize` (wrappers/vec_normalize.hpp) removes that difference: its copies are in
// batched mode, where reset() and step() only keep the original observation, and the VecEnv's
// step hook updates the statistics with the whole batch and then normalises every column, as
// VecNormalize.step_wait does.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/wrappers/running_statistics_wrapper.hpp"

namespace rlrun {

class NormalizeObservation : public RunningStatisticsWrapper {
 public:
  struct Config {
    double clip_obs = 10.0;                  // SB3 VecNormalize clip_obs
    double epsilon = 1e-8;                   // SB3 VecNormalize epsilon
    std::vector<std::string> norm_obs_keys;  // Dict keys normalised; [] = every Box key
    std::optional<int64_t> freeze_after;     // observations before the statistics freeze
    template <class V>
    void visit(V& v) {
      v("clip_obs", clip_obs, "normalised observations are clipped to [-clip_obs, clip_obs]",
        positive());
      v("epsilon", epsilon, "added to the variance before the square root", positive());
      v("norm_obs_keys", norm_obs_keys,
        "Dict observations: the Box keys to normalise ([] = every Box key; SB3 norm_obs_keys)");
      v("freeze_after", freeze_after,
        "stop updating the statistics once they hold this many observations (null: never)",
        at_least(1));
    }
  };
  // Throws std::invalid_argument for an observation space that is not a Box or a Dict with a
  // Box key, a norm_obs_keys entry that is not a Box key of the Dict, or clip_obs <= 0.
  NormalizeObservation(EnvPtr inner, const Config& config);
  explicit NormalizeObservation(EnvPtr inner) : NormalizeObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  std::string statistics_name() const override { return "NormalizeObservation"; }
  void share_statistics_with(ModelStatistics& first) override;

  // Batched mode (set_batched; wrappers/vec_normalize.hpp): reset() and step() pass
  // observations through; update_batch() and normalize() do the work for the whole VecEnv.
  // While training: SB3's obs_rms.update(obs) with one observation per column of `obs`
  // (observations of this wrapper's inner space).
  void update_batch(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // Normalises one observation in place with the current statistics.
  void normalize(std::span<float> obs) const;
  // Deploying: normalize() with the frozen statistics, as graph nodes.
  std::string export_observation(PolicyGraph& graph, const std::string& obs) const override;
  std::string export_action(PolicyGraph& /*graph*/, const std::string& action) const override {
    return action;
  }
  // The observation of the last reset()/step() before normalisation (SB3 get_original_obs).
  std::span<const float> original_obs() const { return original_; }

 protected:
  void write_own_state(StateWriter& out) const override {
    StateWriter own = out.sub("normalize_observation");
    rms_->write(own);
  }
  void read_own_state(const StateReader& in) override {
    rms_->read(in.sub("normalize_observation"));
  }

 private:
  StepResult after_step(StepResult result, std::span<float> obs) override;
  // The floats the statistics see: the observation itself, or its normalised keys' floats.
  std::span<const float> selected(std::span<const float> obs);

  Config config_;
  bool whole_ = true;          // every float is normalised (a Box observation)
  std::vector<int> indices_;   // else: the normalised floats' positions
  std::vector<float> picked_;  // their values, for the statistics
  Space space_;
  // Whether this observation goes into the statistics: while training, until freeze_after.
  bool updating() const {
    return training_ &&
           (!config_.freeze_after || rms_->count() < static_cast<double>(*config_.freeze_after));
  }
  std::vector<float> batch_scratch_;  // update_batch()'s float32 moments
  std::vector<float> original_;
};

}  // namespace rlrun
