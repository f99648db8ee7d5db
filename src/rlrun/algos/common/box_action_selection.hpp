#pragma once
// How SAC, TD3 and DDPG act in a Box action space, SB3 OffPolicyAlgorithm._sample_action:
// before learning_starts a uniform sample of the action space per env (then scale_action);
// afterwards the policy's action, already in [-1, 1] (a tanh-squashed actor); in both cases
// the exploration noise added and the result clipped to [-1, 1], which is what the replay
// buffer stores; the env gets it unscaled to [low, high] (unscale_action). The actors end in
// tanh, so the Box must be bounded.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class PolicyGraph;

class BoxActionSelection {
 public:
  // Throws std::invalid_argument, naming the algorithm `id`, unless the observations are a Box
  // and the actions a Box with finite bounds low < high. Returns the action dimension.
  static int checked_action_dim(const AlgorithmSetup& setup, const std::string& id);

  // The action stream is seed ^ kActionStream and the noise stream seed ^ kNoiseStream
  // (rng_streams.hpp). Throws std::invalid_argument for an unknown noise type.
  BoxActionSelection(const AlgorithmSetup& setup, const ActionNoiseConfig& noise);

  // Actions for obs (obs_dim x n_envs): `policy(action_rng, buffer_actions)` writes the
  // policy's actions in [-1, 1] (it may draw from action_rng, SAC's sampling does) unless
  // `warmup`. buffer_actions end in [-1, 1], env_actions in [low, high].
  template <class Policy>
  void select(const Eigen::MatrixXf& obs, bool warmup, Policy&& policy,
              Eigen::MatrixXf& env_actions, Eigen::MatrixXf& buffer_actions) {
    if (warmup) {
      sample_uniform(obs.cols(), env_actions, buffer_actions);
    } else {
      policy(action_rng_, buffer_actions);
    }
    add_noise(buffer_actions);
    to_env_actions(buffer_actions, env_actions);
  }

  // SB3 unscale_action: [-1, 1] -> [low, high], clamped so that rounding at +-1 never leaves
  // the Box (predict() uses it too).
  void to_env_actions(const Eigen::MatrixXf& scaled, Eigen::MatrixXf& env_actions) const;
  // The same as graph nodes (nn/policy_graph.hpp): an affine map and a clamp.
  std::string export_env_actions(PolicyGraph& graph, const std::string& scaled) const;

  // SB3 collect_rollouts: action_noise.reset(indices=[env]) when an episode ends.
  void on_episode_end(int env) { noise_.reset(env); }

  // Exact resume: both RNG streams and the Ornstein-Uhlenbeck state.
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);
  Rng& action_rng() { return action_rng_; }
  Rng& noise_rng() { return noise_rng_; }
  ActionNoise& noise() { return noise_; }

 private:
  // np.array([action_space.sample() for _ in range(n_envs)]), then scale_action.
  void sample_uniform(Eigen::Index n, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions);
  // clip(actions + noise(), -1, 1) when there is noise (SB3 adds it in warmup too).
  void add_noise(Eigen::MatrixXf& buffer_actions);

  Space space_;
  Rng action_rng_, noise_rng_;
  ActionNoise noise_;
  Eigen::MatrixXf noise_sample_;
};

// gSDE's exploration matrices while collecting (SAC, TQC, CrossQ; SB3 collect_rollouts):
// reset_noise(n_envs) when a collection starts, then, with sde_sample_freq > 0, whenever
// num_collected_steps % sde_sample_freq == 0 (so twice at the start), from the current log_std.
template <class Actor>
void reset_collect_noise(Actor& acting, Rng& rng, int n_envs, int64_t collected_steps,
                         int sde_sample_freq) {
  if (collected_steps == 0) acting.reset_noise(rng, n_envs);
  if (sde_sample_freq > 0 && collected_steps % sde_sample_freq == 0)
    acting.reset_noise(rng, n_envs);
}

// The acting copy of SAC's or TD3's actor: a separate network, so that acting on a few
// observations never resizes the training network's buffers. It takes the trained weights when
// they changed (invalidate() after each optimizer step or load).
template <class Actor>
class ActingCopy {
 public:
  explicit ActingCopy(const Actor& trained) : trained_(&trained), copy_(trained) {}
  void invalidate() { stale_ = true; }
  Actor& get() {
    if (stale_) {
      // Same sizes: copies, no allocation. An actor with more parameters than its network
      // (SAC's gSDE log_std) says how to copy them.
      if constexpr (requires(Actor & to, const Actor& from) { to.copy_parameters_from(from); })
        copy_.copy_parameters_from(*trained_);
      else
        copy_.net().params() = trained_->net().params();
      stale_ = false;
    }
    return copy_;
  }

 private:
  const Actor* trained_;
  Actor copy_;
  bool stale_ = true;
};

}  // namespace rlrun
