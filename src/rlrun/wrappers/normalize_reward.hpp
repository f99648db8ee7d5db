#pragma once
// NormalizeReward: the reward half of SB3's VecNormalize
// (stable_baselines3/common/vec_env/vec_normalize.py). Rewards are divided by the running
// standard deviation of the discounted return, not of the reward:
//     while training:  ret = ret * gamma + reward;  ret_rms.update(ret)
//     reward' = clip(reward / sqrt(ret_rms.var + epsilon), -clip_reward, clip_reward)
//     ret = 0 when the episode ends (and on reset)
// The return `ret` is per env; ret_rms is shared by the n copies of a training VecEnv, like
// VecNormalize's single ret_rms (see normalize_observation.hpp for the one difference: within
// a VecEnv step, env i sees the statistics with envs 0..i added). With n_envs = 1 the rewards
// are bit-identical to SB3's.
// Put it after the Monitor (rlrun always does): episode returns in monitor.csv, progress.csv
// and evaluations stay the env's true rewards. `gamma` is VecNormalize's own (0.99 by
// default); rl-zoo passes the algorithm's gamma, so set it to the same value to match.
#include <memory>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/wrappers/running_statistics_wrapper.hpp"

namespace rlrun {

class NormalizeReward : public RunningStatisticsWrapper {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  struct Config {
    double gamma = 0.99;        // SB3 VecNormalize gamma (discount of the return whose std is used)
    double clip_reward = 10.0;  // SB3 VecNormalize clip_reward
    double epsilon = 1e-8;      // SB3 VecNormalize epsilon
    template <class V>
    void visit(V& v) {
      v("gamma", gamma, "discount of the running return whose standard deviation scales rewards",
        unit_interval());
      v("clip_reward", clip_reward, "scaled rewards are clipped to [-clip_reward, clip_reward]",
        positive());
      v("epsilon", epsilon, "added to the variance before the square root", positive());
    }
  };
  // Throws std::invalid_argument for gamma outside [0, 1] or clip_reward <= 0.
  NormalizeReward(EnvPtr inner, const Config& config);
  explicit NormalizeReward(EnvPtr inner) : NormalizeReward(std::move(inner), Config()) {}

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  std::string statistics_name() const override { return "NormalizeReward"; }
  void share_statistics_with(ModelStatistics& first) override;

  double discounted_return() const { return return_; }

  // Batched mode (set_batched; wrappers/vec_normalize.hpp): reset() and step() pass rewards
  // through and leave the return alone; the VecEnv's hook calls the functions below.
  // Frozen (training false): rewards pass unchanged instead of being scaled.
  void set_unscaled_when_frozen(bool unscaled) { unscaled_when_frozen_ = unscaled; }
  // While training: ret = ret * gamma + reward. Returns ret.
  double add_to_return(double reward);
  // While training: ret_rms.update(returns) with the batch of every copy's return.
  void update_batch(std::span<const double> returns, std::span<double> scratch);
  // clip(reward / sqrt(ret_rms.var + epsilon)) (unchanged when frozen and so configured).
  double scale(double reward) const;
  void end_episode() { return_ = 0.0; }

 protected:
  void write_own_state(StateWriter& out) const override;
  void read_own_state(const StateReader& in) override;

 private:
  StepResult after_step(StepResult result, std::span<float> obs) override;
  Config config_;
  double return_ = 0.0;
  bool unscaled_when_frozen_ = false;
};

}  // namespace rlrun
