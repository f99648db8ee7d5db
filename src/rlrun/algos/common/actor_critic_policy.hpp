#pragma once
// SB3's ActorCriticPolicy for MlpPolicy (stable_baselines3/common/policies.py), used by PPO and
// A2C: separate actor and critic towers (net_arch [64, 64] each by default since SB3 1.8),
// orthogonal init with gains sqrt(2) (towers), 0.01 (action_net) and 1 (value_net), and the
// action distribution SB3's make_proba_distribution (common/distributions.py) picks: Categorical
// for Discrete, MultiCategorical for MultiDiscrete, Bernoulli for MultiBinary, and a diagonal
// Gaussian with a state-independent `log_std` parameter for Box actions — or, with use_sde,
// gSDE's StateDependentNoiseDistribution on the actor's latent features (learn_features false:
// the latent is detached, as SB3's ActorCriticPolicy sets it).
// With `maskable` it is sb3-contrib 2.4's MaskableActorCriticPolicy
// (sb3_contrib/common/maskable/policies.py): the same networks and initialisation, masks
// applied to the logits before the distribution (nn/action_masking.hpp), and MultiBinary as
// one two-way categorical per entry (MaskableBernoulliDistribution: 2n logits).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/env/observation_encoder.hpp"
#include "rlrun/nn/bernoulli.hpp"
#include "rlrun/nn/categorical.hpp"
#include "rlrun/nn/diag_gaussian.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/multi_categorical.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/nn/state_dependent_noise.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

struct ActorCriticPolicyConfig;
// The checks PPO and A2C share: spaces, network shape and the memory of the networks and of a
// rollout of `rollout_size` (n_steps * n_envs) steps, minibatches of `batch`.
ConfigProblems check_actor_critic(const ActorCriticPolicyConfig& policy, int64_t rollout_size,
                                  int64_t batch, const AlgorithmSetup& setup);

// Outputs of SB3's action_net for an action space (proba_distribution_net): n for Discrete(n)
// and MultiBinary(n), sum(nvec) for MultiDiscrete, the dimension for Box. Throws
// std::invalid_argument for a Dict.
int action_net_size(const Space& action_space);

struct ActorCriticPolicyConfig {
  NetArchPiVf net_arch = {{64, 64}, {64, 64}};   // actor (pi) and critic (vf) hidden sizes
  Activation activation_fn = Activation::kTanh;  // SB3 default nn.Tanh
  bool ortho_init = true;     // orthogonal init with SB3's gains; false: torch's default init
  double log_std_init = 0.0;  // initial log std of Gaussian actions
  bool full_std = true;       // gSDE: a std per (latent feature, action)
  bool use_expln = false;     // gSDE: expln instead of exp for the std
  // SB3 policy_kwargs: features_extractor_class (and features_extractor_kwargs' features_dim),
  // normalize_images, share_features_extractor.
  FeaturesExtractor features_extractor_class = FeaturesExtractor::kFlatten;
  int features_dim = 512;
  int cnn_output_dim = 256;
  bool normalize_images = true;
  bool share_features_extractor = true;

  FeaturesExtractorSettings extractor() const {
    return {features_extractor_class, features_dim, cnn_output_dim, normalize_images};
  }

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, kNetArchPiVfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    v("ortho_init", ortho_init,
      "orthogonal init (gains sqrt(2), 0.01 actor head, 1 critic head); false: torch's default "
      "Linear init");
    v("log_std_init", log_std_init, "initial log standard deviation for Box actions",
      in_range(-20, 20));
    v("full_std", full_std,
      "gSDE (use_sde): log_std per latent feature and action (true) or per feature (false)");
    v("use_expln", use_expln, "gSDE (use_sde): expln instead of exp keeps the std positive");
    visit_features_extractor(v, features_extractor_class, features_dim, cnn_output_dim);
    v("normalize_images", normalize_images, kNormalizeImagesDoc);
    v("share_features_extractor", share_features_extractor,
      "actor and critic read one NatureCNN (SB3's default for PPO and A2C); false: one each");
  }
};

// An action distribution's parameters for a batch, as TRPO keeps the old one (sb3-contrib's
// old_distribution): the actor's output (logits or means, one column per sample) and, for
// Gaussian actions, the standard deviations (action_dim x n).
struct ActionDistributionParams {
  Eigen::MatrixXf head;
  Eigen::MatrixXf sigma;
};

class ActorCriticPolicy {
 public:
  // The distribution over actions, from the action space's kind.
  enum class Head {
    kCategorical,
    kMultiCategorical,
    kBernoulli,
    kDiagGaussian,
    kStateDependentNoise
  };

  // Observations of any space (ObservationEncoder: one-hots for Discrete values, Dict keys
  // concatenated); actions of any space but Dict (std::invalid_argument). use_sde (Box actions
  // only, else std::invalid_argument) picks gSDE; its first exploration matrix is drawn from
  // init_rng after the weights, as SB3's proba_distribution_net samples one.
  // `maskable` (Discrete, MultiDiscrete and MultiBinary actions, else std::invalid_argument)
  // makes the masked policy: act() and evaluate_actions() then take masks.
  ActorCriticPolicy(const Space& observation_space, const Space& action_space,
                    const ActorCriticPolicyConfig& config, Rng& init_rng, bool use_sde = false,
                    bool maskable = false);

  Head head() const { return head_; }
  // Box actions: a Gaussian with the learned log_std (SB3 logs train/std).
  bool gaussian() const {
    return head_ == Head::kDiagGaussian || head_ == Head::kStateDependentNoise;
  }
  bool use_sde() const { return head_ == Head::kStateDependentNoise; }
  // SB3 reset_noise(n_envs): new exploration matrices (gSDE only; std::logic_error otherwise).
  void reset_noise(Rng& rng, int n_envs);
  // The gSDE distribution (its log_std and exploration matrices); empty without use_sde.
  const StateDependentNoise& sde() const { return sde_; }
  StateDependentNoise& sde() { return sde_; }
  // Floats per action (the rollout buffer's rows): 1 for Discrete, one per entry otherwise.
  int action_dim() const { return action_dim_; }
  // Entries of one observation's action mask (env/action_mask.hpp), 0 for an unmasked policy.
  int mask_size() const { return mask_size_; }

  // `obs` are the env's observations (input_dim x n) everywhere below; the policy encodes them.
  // Rollout step: actions (act_dim x n, as sampled: unclipped), values and log-probs. `masks`
  // (mask_size() x n of 0/1, maskable policies only; null: no masking, as sb3-contrib's
  // action_masks=None) remove illegal actions from the distribution.
  void act(const Eigen::Ref<const Eigen::MatrixXf>& obs, Rng& rng, bool deterministic,
           Eigen::MatrixXf& actions, Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_probs,
           const Eigen::MatrixXf* masks = nullptr);
  void predict_values(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::RowVectorXf& values);

  // Training forward pass (SB3 evaluate_actions); keeps what backward() needs. `masks` as in
  // act(): log-probs and entropy of the masked distribution (sb3-contrib evaluate_actions).
  void evaluate_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                        const Eigen::Ref<const Eigen::MatrixXf>& actions,
                        Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_prob,
                        Eigen::RowVectorXf& entropy, const Eigen::MatrixXf* masks = nullptr);
  // Adds the gradients of a loss with the given partial derivatives w.r.t. the outputs of the
  // last evaluate_actions() to every parameter's gradient.
  void backward(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy);

  // TRPO (algos/trpo/; defined in actor_critic_fisher.cpp). The actor's parameters as one
  // vector: the actor tower with action_net, then log_std (sb3-contrib's actor_params, every
  // parameter the KL divergence reaches). Only for policies without a learned features
  // extractor (std::logic_error otherwise).
  Eigen::Index actor_param_count() const;
  void get_actor_params(Eigen::VectorXf& theta) const;
  void set_actor_params(const Eigen::VectorXf& theta);
  // The actor parameters' gradient (after backward()), in the same layout.
  void get_actor_grads(Eigen::VectorXf& grad) const;
  // The distribution of the last evaluate_actions().
  ActionDistributionParams distribution() const;
  // kl_divergence(distribution, old).mean() of sb3-contrib's TRPO for the last
  // evaluate_actions(): torch's KL per sample for categoricals (summed over a MultiDiscrete's
  // parts), per entry for Bernoulli and Gaussian actions, averaged over all of them.
  double mean_kl(const ActionDistributionParams& old) const;
  // F v at the last evaluate_actions(), F the Hessian of that mean KL in the parameters at the
  // old distribution (sb3-contrib's hessian_vector_product without damping): the Fisher
  // information J^T M J of the distribution's parameters, exact. Overwrites the actor's
  // gradients.
  void fisher_vector_product(const Eigen::VectorXf& v, Eigen::VectorXf& out);
  // The critic alone (TRPO's value updates): dL/dV of the last predict_values() into the
  // critic's gradients, and the critic's optimizer blocks.
  void backward_values(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values);
  std::vector<ParamBlock> critic_blocks();

  // Recurrent policies (sb3-contrib's RecurrentActorCriticPolicy, algos/ppo_recurrent/): act(),
  // evaluate_actions() and backward() on inputs the caller computed, the actor tower's `pi_in`
  // and the critic tower's `vf_in` (the LSTMs' outputs), for a policy built on a Box of their
  // width with the Flatten extractor. backward_latents also writes dL/d(pi_in) and dL/d(vf_in)
  // where given.
  void act_on_latents(const Eigen::Ref<const Eigen::MatrixXf>& pi_in,
                      const Eigen::Ref<const Eigen::MatrixXf>& vf_in, Rng& rng, bool deterministic,
                      Eigen::MatrixXf& actions, Eigen::RowVectorXf& values,
                      Eigen::RowVectorXf& log_probs, const Eigen::MatrixXf* masks = nullptr);
  void evaluate_latents(const Eigen::Ref<const Eigen::MatrixXf>& pi_in,
                        const Eigen::Ref<const Eigen::MatrixXf>& vf_in,
                        const Eigen::Ref<const Eigen::MatrixXf>& actions,
                        Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_prob,
                        Eigen::RowVectorXf& entropy, const Eigen::MatrixXf* masks = nullptr);
  void backward_latents(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                        const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                        const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                        Eigen::MatrixXf* grad_pi_in, Eigen::MatrixXf* grad_vf_in);

  void zero_grad();
  std::vector<ParamBlock> param_blocks();
  // exp(log_std).mean(), SB3's train/std (over the log_std matrix with gSDE); NaN without a
  // Gaussian head.
  double mean_std() const;

  // SB3 state_dict names: mlp_extractor.policy_net.0.weight, action_net.weight, log_std, ...
  // (gSDE's log_std is latent_dim x action_dim, or latent_dim x 1 without full_std).
  void save(TensorMap& tensors) const;
  void load(const TensorMap& tensors);

  // Deploying (nn/policy_graph.hpp): the deterministic act() from `obs` as graph nodes
  // (encoding, actor, the distribution's mode: argmax per categorical part, x > 0 for
  // Bernoulli, the mean for Gaussians and gSDE) and, with `with_value`, the critic's V(s).
  // A maskable policy exports its unmasked mode: the graph has no mask input.
  // `action_space` is the one the policy was built for. Sets the graph's action and value.
  void export_to(PolicyGraph& graph, const std::string& obs, const Space& action_space,
                 bool with_value) const;
  // The critic's V(s) of `obs` alone as graph nodes; returns its tensor (RecurrentPPO's critic
  // reads another latent than its actor).
  std::string export_value(PolicyGraph& graph, const std::string& obs) const;

  // The threads a training minibatch's actor and critic passes share (null, the default: the
  // calling thread alone). Never changes a result: the two write separate networks.
  void set_thread_pool(ThreadPool* pool) {
    pool_ = pool;
    extractor_.set_thread_pool(pool);
    vf_extractor_.set_thread_pool(pool);
  }

  const ObservationEncoder& encoder() const { return encoder_; }
  // SB3's CnnPolicy: the NatureCNN (the actor's, shared with the critic unless
  // share_features_extractor is false; a CombinedExtractor's first), or null without one.
  const NatureCnn* cnn() const { return extractor_.learned() ? &extractor_.cnn() : nullptr; }
  // The critic's own NatureCNN when share_features_extractor is false, else null.
  const NatureCnn* value_cnn() const {
    return separate_value_extractor_ ? &vf_extractor_.cnn() : nullptr;
  }
  const FeaturesExtractorNet& features_extractor() const { return extractor_; }
  const Mlp& actor() const { return actor_; }
  const Mlp& critic() const { return critic_; }

 private:
  void run_pair(Eigen::Index batch, const std::function<void()>& actor_part,
                const std::function<void()>& critic_part);
  // The head, action_dim_ and mask_size_ for an action space (sb3-contrib's
  // make_masked_proba_distribution with `maskable`, else SB3's make_proba_distribution).
  void choose_distribution(const Space& action_space, bool maskable);
  // TRPO's helpers (actor_critic_fisher.cpp): the Gaussian standard deviations of the last
  // evaluate_actions() (action_dim x n; empty for other heads), and the categoricals' sizes
  // (one part for Discrete).
  Eigen::MatrixXf gaussian_sigma() const;
  std::vector<int64_t> categorical_part_sizes() const;
  // std::logic_error for masks given to a policy built without masking.
  void check_masks(const Eigen::MatrixXf* masks) const;
  // The heads' input for a batch of observations: the encoding through the features extractor
  // (whose networks then keep what their backward needs).
  Eigen::Ref<const Eigen::MatrixXf> features(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // The critic's input: `actor_features` when the extractor is shared, else the observations
  // through the critic's own CNN (SB3 vf_features_extractor).
  Eigen::Ref<const Eigen::MatrixXf> value_features(
      const Eigen::Ref<const Eigen::MatrixXf>& obs,
      const Eigen::Ref<const Eigen::MatrixXf>& actor_features);

  ThreadPool* pool_ = nullptr;
  ObservationEncoder encoder_;
  // SB3's features_extractor (pi_features_extractor when not shared) and, with
  // share_features_extractor false and an extractor that learns, the critic's own
  // vf_features_extractor.
  FeaturesExtractorNet extractor_;
  bool separate_value_extractor_ = false;
  FeaturesExtractorNet vf_extractor_;
  Eigen::MatrixXf grad_features_, grad_features_critic_;  // dL/d(features), per head
  Head head_ = Head::kDiagGaussian;
  int action_dim_ = 1;
  int mask_size_ = 0;
  std::vector<int64_t> categorical_parts_;  // the categoricals' sizes (multi-categorical heads)
  Eigen::VectorXf low_, high_;
  Mlp actor_, critic_;
  Eigen::VectorXf log_std_, log_std_grad_;
  Categorical categorical_;
  MultiCategorical multi_categorical_;
  Bernoulli bernoulli_;
  DiagGaussian gaussian_;
  StateDependentNoise sde_;
  // Workspaces for backward.
  Eigen::MatrixXf actions_, grad_head_, gaussian_sample_;
  Eigen::MatrixXf masks_;      // evaluate_actions' masks, for backward
  bool masked_batch_ = false;  // the last evaluate_actions() had masks
  Eigen::VectorXf grad_log_std_batch_;
  Eigen::RowVectorXf action_row_;
};

// Writes an Mlp's layers under SB3 names: hidden layer i -> `<tower>.<2i>.weight/bias`
// (torch Sequential indices skip the activations), the output layer -> `<head>.weight/bias`.
void save_mlp(const Mlp& mlp, const std::string& tower, const std::string& head, TensorMap& out);
void load_mlp(Mlp& mlp, const std::string& tower, const std::string& head, const TensorMap& in);

}  // namespace rlrun
