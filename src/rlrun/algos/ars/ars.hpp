#pragma once
// Augmented Random Search (Mania, Guy and Recht 2018, "Simple random search provides a
// competitive approach to reinforcement learning", arXiv:1803.07055) with sb3-contrib 2.4's
// semantics, defaults and key names (sb3_contrib/ars/ars.py, ars/policies.py). Per update:
//   1. n_delta directions d_k ~ N(0, I) over the policy's parameters; candidates
//      w + delta_std d_k and w - delta_std d_k (all the plus ones, then all the minus ones);
//   2. each candidate's return: n_eval_episodes episodes on the training env as SB3's
//      evaluate_policy runs them (a reset first, episodes shared out over the envs), summed, plus
//      alive_bonus_offset per step;
//   3. the n_top directions whose better candidate is best; with sigma the std of their 2 n_top
//      returns, w += learning_rate / (n_top sigma + 1e-6) sum_k (r+_k - r-_k) d_k.
// The policy is ARSPolicy: an MLP (net_arch [64, 64], ReLU) with tanh at the end for Box actions
// (squash_output), then scaled to the bounds; argmax of the outputs for Discrete actions. The
// zoo's LinearPolicy is net_arch [], with_bias false, squash_output false (clipped actions).
// Weights start at zero (zero_policy) or at torch's Linear init.
//
// Candidates are evaluated one after the other on the env the run trains on, whose copies step
// across the run's threads (env/vec_env.hpp); statistics of env.normalize keep updating during
// the evaluations, as with sb3-contrib's evaluation in the training process (its AsyncEval, a
// process per worker, is not built). Env steps count as evaluate_policy's callback counts them:
// n_envs per env still collecting episodes, per step.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/resumable_algorithm.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/env/observation_encoder.hpp"
#include "rlrun/nn/activation.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

// sb3-contrib ARSPolicy's constructor arguments (MlpPolicy's defaults).
struct ArsPolicyConfig {
  std::vector<int> net_arch = {64, 64};
  Activation activation_fn = Activation::kReLU;
  bool with_bias = true;
  bool squash_output = true;

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, "hidden layer sizes ([] = linear; the zoo's LinearPolicy)",
      layer_width());
    v("activation_fn", activation_fn, "activation between hidden layers");
    v("with_bias", with_bias, "layers learn a bias (LinearPolicy: false)");
    v("squash_output", squash_output,
      "Box actions: tanh then scaled to the bounds (false: clipped to them; LinearPolicy)");
  }
};

class ARS : public ResumableAlgorithm {
 public:
  // sb3-contrib ARS.__init__'s parameters and defaults.
  struct Config {
    int n_delta = 8;
    std::optional<int> n_top;  // null: n_delta
    Schedule learning_rate = Schedule::constant(0.02);
    Schedule delta_std = Schedule::constant(0.05);
    bool zero_policy = true;
    double alive_bonus_offset = 0.0;
    int n_eval_episodes = 1;
    ArsPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("n_delta", n_delta, "random directions per update (2 n_delta candidates)",
        in_range(1, 1e6));
      v("n_top", n_top, "directions kept for the step (null = n_delta; above n_delta: n_delta)",
        in_range(1, 1e6));
      v("learning_rate", learning_rate, "step size: a number or lin_<initial>", non_negative());
      v("delta_std", delta_std, "exploration noise scale: a number or lin_<initial>", positive());
      v("zero_policy", zero_policy, "start from all-zero weights");
      v("alive_bonus_offset", alive_bonus_offset,
        "added to a candidate's return per env step (e.g. -1 removes a locomotion alive bonus)");
      v("n_eval_episodes", n_eval_episodes, "episodes per candidate", in_range(1, 1e6));
      v("policy", policy, "network: net_arch, activation_fn, with_bias, squash_output");
    }
  };

  // sb3-contrib ARS's supported_action_spaces.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox, SpaceKind::kDiscrete};

  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  ARS(const Config& config, const AlgorithmSetup& setup);

  std::string id() const override { return "ARS"; }
  void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // sb3-contrib's tensor names: action_net.<2i>.weight / .bias (torch Sequential indices).
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;

  // The learned parameters as one vector (biases left out without with_bias), and back.
  Eigen::VectorXf weights() const;
  void set_weights(const Eigen::VectorXf& weights);
  // sb3-contrib's _do_one_update after the evaluations: the step from the candidates' returns
  // (plus ones, then minus ones) and the directions (n_delta x n_params). Returns the step
  // size, sets return_std.
  double apply_update(const Eigen::VectorXd& candidate_returns, const Eigen::MatrixXf& deltas,
                      double learning_rate, double& return_std);

 private:
  // evaluate_policy(candidate, env, n_eval_episodes) with candidate_net_: the summed returns
  // plus the alive bonus. keep_going turns false when a hook asked to stop.
  double evaluate_candidate(VecEnv& env, TrainingHooks& hooks, bool& keep_going);
  // ARSPolicy.forward then predict's scaling or clipping, with the given network.
  void act(Mlp& net, const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions);
  void record_update(Logger& log, double delta_std, double learning_rate, double step_size,
                     double return_std) const;

  Config config_;
  int n_top_;
  Space action_space_;
  ObservationEncoder encoder_;
  Mlp net_;
  // The candidate being evaluated (sb3-contrib's train_policy, a deep copy): callbacks that act
  // during the evaluations (an eval every N steps) see net_, the current weights.
  Mlp candidate_net_;
  std::vector<Eigen::Index> learned_;  // indices into net_.params() that ARS moves
  Rng rng_;
  int64_t n_updates_ = 0;
  std::vector<double> episode_returns_, episode_lengths_;  // this update's episodes
  Eigen::MatrixXf obs_, actions_;
};

}  // namespace rlrun
