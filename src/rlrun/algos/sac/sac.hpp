#pragma once
// Soft Actor-Critic (Haarnoja et al. 2018, arXiv:1801.01290 and arXiv:1812.05905) with SB3 2.x
// semantics, defaults and key names (stable_baselines3/sac/sac.py, sac/policies.py,
// common/off_policy_algorithm.py; CleanRL's sac_continuous_action.py is the same update in
// one file): a tanh-squashed Gaussian actor, n_critics (2) Q-networks on concat(obs, action)
// with Polyak-averaged targets, clipped double-Q soft Bellman targets, and an entropy
// coefficient that is fixed or learned towards target_entropy. Actions live in [-1, 1] inside
// the algorithm (replay buffer, critics, noise) and are rescaled to the Box bounds for the env.
//
// One gradient step (train_on_batch) reads top to bottom like SAC.train. A training-sized
// minibatch is split over two SacLane replicas (algos/common/batch_lanes.hpp) that run on both
// cores when ForkJoin's worker is on (RLRUN_THREADS=2), one after the other otherwise. The
// split depends on the batch size only, so a run is bit-identical either way.
#include <optional>
#include <string>
#include <vector>

#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/algos/common/box_action_selection.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/sac/entropy_coefficient.hpp"
#include "rlrun/algos/sac/sac_actor.hpp"
#include "rlrun/algos/sac/sac_lane.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

// SB3 SACPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo).
struct SacPolicyConfig {
  std::vector<int> net_arch = {256, 256};  // hidden sizes of the actor and of each critic
  std::string activation_fn = "relu";      // relu or tanh (SB3 default nn.ReLU)
  int n_critics = 2;                       // number of Q-networks (clipped double-Q: 2)

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, "hidden layer sizes of the actor and of each critic", layer_width());
    v("activation_fn", activation_fn, "activation between hidden layers: relu or tanh",
      activation_names());
    v("n_critics", n_critics, "number of Q-networks; targets use their minimum", in_range(1, 100));
  }
};

// The per-step scalars SAC.train records (means over a train() call are logged).
struct SacStepStats {
  double ent_coef = 0.0;       // alpha used in this step (before its update)
  double ent_coef_loss = 0.0;  // 0 when alpha is fixed
  double actor_loss = 0.0;
  double critic_loss = 0.0;  // 0.5 * sum over critics of mse
};

class SAC : public Algorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(3e-4);
    OffPolicyConfig off_policy;  // SB3 SAC defaults: 1e6, 100, 256, 0.005, 0.99, 1, 1
    std::string ent_coef = "auto";
    int target_update_interval = 1;
    std::string target_entropy = "auto";
    SacPolicyConfig policy;
    ActionNoiseConfig action_noise;  // none by default

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate,
        "Adam step size of actor, critics and ent_coef: a number or lin_<initial>", non_negative());
      off_policy.visit(v);
      action_noise.visit(v);
      v("ent_coef", ent_coef, "entropy coefficient: auto, auto_<initial> (learned) or a number",
        EntCoefSpec{});
      v("target_update_interval", target_update_interval,
        "soft-update the target critics every N gradient steps of a train() call", at_least(1));
      v("target_entropy", target_entropy,
        "entropy target when ent_coef is learned: auto (-dim A) or a number", TargetEntropySpec{});
      v("policy", policy, "networks: net_arch, activation_fn, n_critics");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Throws std::invalid_argument for bad settings or spaces (Box observations; bounded Box
  // actions).
  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  SAC(const Config& config, const AlgorithmSetup& setup);
  SAC(const SAC&) = delete;
  SAC& operator=(const SAC&) = delete;

  std::string id() const override { return "SAC"; }
  void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) override;
  // tanh(mu) (deterministic) or a sample, rescaled to the Box bounds.
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;
  // Resume: counters, RNG streams, exploration noise, every Adam's moments and the replay
  // buffer (the networks, targets included, are in the model tensors).
  void save_training_state(StateWriter& out) const override;
  void load_training_state(const StateReader& in) override;

  // One gradient step of SAC.train on `batch` (actions in [-1, 1]) with learning rate lr;
  // update_target applies the Polyak update afterwards. Public for tests and benchmarks.
  SacStepStats train_on_batch(const ReplayBatch& batch, float lr, bool update_target);

  // SB3 OffPolicyAlgorithm._sample_action: warmup = uniform samples of the action space,
  // otherwise a stochastic actor sample; exploration noise added and clipped to [-1, 1].
  // buffer_actions in [-1, 1], env_actions in [low, high].
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions);

  const Config& config() const { return config_; }
  // The trained networks (the primary lane's).
  const SacActor& actor() const { return lanes_.front().actor(); }
  SacActor& actor() { return lanes_.front().actor(); }
  const std::vector<ContinuousCritic>& critics() const { return lanes_.front().critics(); }
  std::vector<ContinuousCritic>& critics() { return lanes_.front().critics(); }
  const EntropyCoefficient& ent_coef() const { return ent_coef_; }
  int64_t n_updates() const { return n_updates_; }
  // From the last train_on_batch: the soft Bellman target y (1 x batch) and the standard
  // normal noise used for the next actions and for the policy's actions (action_dim x batch).
  const Eigen::MatrixXf& last_critic_target() const { return target_q_; }
  const Eigen::MatrixXf& last_next_noise() const { return next_noise_; }
  const Eigen::MatrixXf& last_policy_noise() const { return policy_noise_; }

 private:
  // `gradient_steps` updates from the replay buffer (SB3 SAC.train), logging the means.
  void train(int gradient_steps, Logger* logger);
  void resize_workspaces(Eigen::Index batch);
  // The acting copy of the actor (a separate Mlp so that batch-1 acting never resizes the
  // training network's buffers) gets the trained weights when they changed.
  void sync_acting_actor();

  Config config_;
  AlgorithmSetup setup_;
  int obs_dim_ = 0;
  int action_dim_ = 0;
  Rng init_rng_, sample_rng_, train_rng_, predict_rng_;
  std::vector<SacLane> lanes_;  // [0] holds the trained parameters; [1] a replica
  Adam actor_optimizer_;
  std::vector<Adam> critic_optimizers_;  // one per critic, on lanes_[0]'s parameters
  EntropyCoefficient ent_coef_;
  SacActor acting_actor_;
  BoxActionSelection acting_;  // warmup samples, exploration noise, scaling to the Box
  bool acting_stale_ = true;
  std::optional<OffPolicyState> state_;  // replay buffer etc., created by off_policy_state()
  // The replay buffer is allocated on first use (learn or resume), not for a model that is
  // only evaluated.
  OffPolicyState& off_policy_state();
  int64_t n_updates_ = 0;

  // Training workspaces (one gradient step allocates nothing while the batch size is
  // unchanged): whole-batch noise, log pi(a_pi|s) and y, the lanes' loss parts.
  ReplayBatch batch_;
  Eigen::MatrixXf policy_noise_, next_noise_, target_q_;
  Eigen::RowVectorXf log_prob_;
  double lane_losses_[2] = {0.0, 0.0};
  // Acting workspaces.
  Eigen::MatrixXf scaled_actions_;
  Eigen::RowVectorXf acting_log_prob_;
};

}  // namespace rlrun
