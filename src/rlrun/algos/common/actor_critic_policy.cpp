#include "rlrun/algos/common/actor_critic_policy.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <cmath>
#include <limits>

#include <stdexcept>
#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/observation_columns.hpp"
#include "rlrun/core/resource_limits.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/image_space.hpp"
#include "rlrun/nn/action_masking.hpp"

namespace rlrun {

namespace {
// The rollout side of a distribution: the mode or a sample, and its log-probability.
template <class Distribution, class Actions>
void draw(Distribution& dist, Rng& rng, bool deterministic, Actions& actions,
          Eigen::RowVectorXf& log_probs) {
  if (deterministic)
    dist.mode(actions);
  else
    dist.sample(rng, actions);
  dist.log_prob(actions, log_probs);
}

// A categorical head's logits, with sb3-contrib's masking when there are masks.
template <class Distribution>
void set_logits(Distribution& dist, const Eigen::MatrixXf& logits, const Eigen::MatrixXf* masks) {
  if (masks)
    dist.set_logits(logits, *masks);
  else
    dist.set_logits(logits);
}

// The training side (SB3 evaluate_actions): log-probability of the taken actions, entropy.
template <class Distribution, class Actions>
void score(Distribution& dist, const Actions& actions, Eigen::RowVectorXf& log_prob,
           Eigen::RowVectorXf& entropy) {
  dist.log_prob(actions, log_prob);
  dist.entropy(entropy);
}
}  // namespace

void save_mlp(const Mlp& mlp, const std::string& tower, const std::string& head, TensorMap& out) {
  const int last = mlp.num_layers() - 1;
  for (int l = 0; l <= last; ++l) {
    const std::string name = l == last ? head : tower + "." + std::to_string(2 * l);
    out[name + ".weight"] = to_tensor(Eigen::MatrixXf(mlp.weight(l)));
    out[name + ".bias"] = to_tensor(Eigen::VectorXf(mlp.bias(l)));
  }
}

void load_mlp(Mlp& mlp, const std::string& tower, const std::string& head, const TensorMap& in) {
  const int last = mlp.num_layers() - 1;
  for (int l = 0; l <= last; ++l) {
    const std::string name = l == last ? head : tower + "." + std::to_string(2 * l);
    from_tensor(in, name + ".weight", mlp.weight(l));
    from_tensor(in, name + ".bias", mlp.bias(l));
  }
}

ConfigProblems check_actor_critic(const ActorCriticPolicyConfig& policy, int64_t rollout_size,
                                  int64_t batch, const AlgorithmSetup& setup) {
  ConfigProblems out;
  if (rollout_size > std::numeric_limits<int>::max())
    out.push_back({"n_steps", "n_steps * n_envs = " + std::to_string(rollout_size) +
                                  " steps per rollout is more than rlrun's limit of 2^31 - 1"});
  check_net_arch(out, "policy.net_arch", policy.net_arch.pi, policy.net_arch.vf);
  const int features = features_extractor_output_dim(
      out, "policy.features_extractor_class", policy.extractor(), setup.observation_space,
      policy.share_features_extractor ? 1 : 2, static_cast<double>(batch));
  const int head = setup.action_space.is_dict() ? 1 : action_net_size(setup.action_space);
  check_network_memory(out, "policy.net_arch", features, policy.net_arch.pi, head, 1,
                       static_cast<double>(batch));
  check_network_memory(out, "policy.net_arch", features, policy.net_arch.vf, 1, 1,
                       static_cast<double>(batch));
  // The rollout: observations (uint8 images as bytes), actions and six per-step numbers
  // (reward, value, log-prob, advantage, return, episode start) in float32.
  const double rollout_bytes = static_cast<double>(rollout_size) *
                               (ObservationColumns::bytes_per_observation(setup.observation_space) +
                                (setup.action_space.flat_dim() + 6.0) * sizeof(float));
  const std::string problem = memory_problem(rollout_bytes, "a rollout of n_steps * n_envs steps");
  if (!problem.empty()) out.push_back({"n_steps", problem});
  return out;
}

int action_net_size(const Space& action_space) {
  switch (action_space.kind()) {
    case SpaceKind::kDiscrete:
    case SpaceKind::kMultiBinary: return static_cast<int>(action_space.n());
    case SpaceKind::kMultiDiscrete: {
      int64_t total = 0;
      for (int64_t n : action_space.nvec()) total += n;
      return static_cast<int>(total);
    }
    case SpaceKind::kBox: return action_space.flat_dim();
    case SpaceKind::kDict: break;
  }
  throw std::invalid_argument("action space " + action_space.describe() +
                              " is not supported (SB3 has no distribution for Dict actions)");
}

ActorCriticPolicy::ActorCriticPolicy(const Space& observation_space, const Space& action_space,
                                     const ActorCriticPolicyConfig& config, Rng& init_rng,
                                     bool use_sde, bool maskable)
    : encoder_(observation_space, encoder_normalizes_images(config.features_extractor_class,
                                                            config.normalize_images)) {
  if (use_sde && !action_space.is_box())
    throw std::invalid_argument("use_sde: gSDE needs a Box action space, not " +
                                action_space.describe());
  choose_distribution(action_space, maskable);
  const Activation act = config.activation_fn;
  // SB3 ActorCriticPolicy: the towers start from the features extractor's output;
  // MlpExtractor's policy_net (net_arch.pi) + action_net, value_net (net_arch.vf) + value head.
  extractor_ =
      FeaturesExtractorNet(config.extractor(), observation_space, encoder_.features_dim(), nullptr);
  separate_value_extractor_ = extractor_.learned() && !config.share_features_extractor;
  if (separate_value_extractor_) vf_extractor_ = extractor_;
  const int obs_dim = extractor_.out_dim();
  actor_ =
      Mlp(obs_dim, config.net_arch.pi, maskable ? mask_size_ : action_net_size(action_space), act);
  critic_ = Mlp(obs_dim, config.net_arch.vf, 1, act);
  if (config.ortho_init) {
    // SB3 policies.py _build: module_gains = {features_extractor: sqrt(2), mlp_extractor:
    // sqrt(2), action_net: 0.01, value_net: 1}, in that order; without a shared extractor the
    // features_extractor entry goes and pi_features_extractor, vf_features_extractor (sqrt(2))
    // come last.
    if (!separate_value_extractor_) extractor_.init_orthogonal(init_rng, std::sqrt(2.0f));
    actor_.init_orthogonal(init_rng, std::sqrt(2.0f), 0.01f);
    critic_.init_orthogonal(init_rng, std::sqrt(2.0f), 1.0f);
    if (separate_value_extractor_) {
      extractor_.init_orthogonal(init_rng, std::sqrt(2.0f));
      vf_extractor_.init_orthogonal(init_rng, std::sqrt(2.0f));
    }
  } else {
    // SB3 ActorCriticPolicy._build skips init_weights: every module keeps torch's default
    // init, drawn as it is made: the extractors (features/pi, then vf), then the towers,
    // action_net, value_net; log_std is still log_std_init (below).
    extractor_.init_torch_default(init_rng);
    if (separate_value_extractor_) vf_extractor_.init_torch_default(init_rng);
    actor_.init_torch_default(init_rng);
    critic_.init_torch_default(init_rng);
  }
  if (use_sde) {
    // SB3 _build: proba_distribution_net(latent_dim=latent_dim_pi, latent_sde_dim=latent_dim_pi).
    head_ = Head::kStateDependentNoise;
    StateDependentNoiseOptions options;
    options.full_std = config.full_std;
    options.use_expln = config.use_expln;
    sde_ = StateDependentNoise(actor_.layer_in(actor_.num_layers() - 1), action_dim_,
                               static_cast<float>(config.log_std_init), options);
    sde_.sample_weights(init_rng, 1);
  }
  log_std_ = Eigen::VectorXf::Constant(head_ == Head::kDiagGaussian ? action_dim_ : 0,
                                       static_cast<float>(config.log_std_init));
  log_std_grad_ = Eigen::VectorXf::Zero(log_std_.size());
}

void ActorCriticPolicy::choose_distribution(const Space& action_space, bool maskable) {
  mask_size_ = maskable ? action_mask_size(action_space) : 0;
  if (maskable && mask_size_ == 0)
    throw std::invalid_argument(
        "action masking needs a Discrete, MultiDiscrete or MultiBinary "
        "action space, not " +
        action_space.describe());
  // SB3 make_proba_distribution: the distribution follows the action space's class.
  switch (action_space.kind()) {
    case SpaceKind::kDiscrete:
      head_ = Head::kCategorical;
      action_dim_ = 1;
      break;
    case SpaceKind::kMultiDiscrete:
      head_ = Head::kMultiCategorical;
      action_dim_ = action_space.flat_dim();
      categorical_parts_ = action_space.nvec();
      multi_categorical_ = MultiCategorical(categorical_parts_);
      break;
    case SpaceKind::kMultiBinary:
      head_ = Head::kBernoulli;
      action_dim_ = action_space.flat_dim();
      if (maskable) {
        // sb3-contrib MaskableBernoulliDistribution: a MaskableMultiCategorical of [2] * n.
        head_ = Head::kMultiCategorical;
        categorical_parts_.assign(static_cast<size_t>(action_dim_), 2);
        multi_categorical_ = MultiCategorical(categorical_parts_);
      }
      break;
    case SpaceKind::kBox:
      head_ = Head::kDiagGaussian;
      action_dim_ = action_space.flat_dim();
      low_ = Eigen::Map<const Eigen::VectorXf>(action_space.low().data(), action_dim_);
      high_ = Eigen::Map<const Eigen::VectorXf>(action_space.high().data(), action_dim_);
      break;
    case SpaceKind::kDict:
      throw std::invalid_argument("ActorCriticPolicy: action space " + action_space.describe() +
                                  " is not supported (SB3 has no distribution for Dict actions)");
  }
}

void ActorCriticPolicy::reset_noise(Rng& rng, int n_envs) {
  if (!use_sde()) throw std::logic_error("reset_noise() is only available when using gSDE");
  sde_.sample_weights(rng, n_envs);
}

void ActorCriticPolicy::check_masks(const Eigen::MatrixXf* masks) const {
  if (masks != nullptr && mask_size_ == 0)
    throw std::logic_error("action masks given to a policy without masking");
}

void ActorCriticPolicy::act(const Eigen::Ref<const Eigen::MatrixXf>& obs, Rng& rng,
                            bool deterministic, Eigen::MatrixXf& actions,
                            Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_probs,
                            const Eigen::MatrixXf* masks) {
  const Eigen::Ref<const Eigen::MatrixXf> features = this->features(obs);
  act_on_latents(features, value_features(obs, features), rng, deterministic, actions, values,
                 log_probs, masks);
}

void ActorCriticPolicy::act_on_latents(const Eigen::Ref<const Eigen::MatrixXf>& pi_in,
                                       const Eigen::Ref<const Eigen::MatrixXf>& vf_in, Rng& rng,
                                       bool deterministic, Eigen::MatrixXf& actions,
                                       Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_probs,
                                       const Eigen::MatrixXf* masks) {
  const Eigen::Index n = pi_in.cols();
  actions.resize(action_dim_, n);
  values.resize(n);
  log_probs.resize(n);
  check_masks(masks);
  const Eigen::MatrixXf& head = actor_.forward(pi_in);
  switch (head_) {
    case Head::kCategorical:
      set_logits(categorical_, head, masks);
      // A 1 x n row of a column-major matrix has a stride; go through a contiguous row.
      action_row_.resize(n);
      draw(categorical_, rng, deterministic, action_row_, log_probs);
      actions.row(0) = action_row_;
      break;
    case Head::kMultiCategorical:
      set_logits(multi_categorical_, head, masks);
      draw(multi_categorical_, rng, deterministic, actions, log_probs);
      break;
    case Head::kBernoulli:
      bernoulli_.set_logits(head);
      draw(bernoulli_, rng, deterministic, actions, log_probs);
      break;
    case Head::kDiagGaussian:
      gaussian_.set(head, log_std_);
      draw(gaussian_, rng, deterministic, actions, log_probs);
      break;
    case Head::kStateDependentNoise:
      // The noise comes from the exploration matrices (reset_noise), not from rng.
      sde_.set(head, actor_.last_hidden());
      if (deterministic)
        sde_.mode(actions);
      else
        sde_.sample(actions);
      sde_.log_prob(actions, log_probs);
      break;
  }
  values = critic_.forward(vf_in);
}

// The categorical parts come from the policy itself (a maskable MultiBinary policy has one per
// entry, which the space's nvec does not list).
void ActorCriticPolicy::export_to(PolicyGraph& graph, const std::string& obs,
                                  const Space& /*action_space*/, bool with_value) const {
  const std::string encoded = encoder_.export_to(graph, obs);
  const std::string features = extractor_.export_to(graph, encoded);
  const std::string head = graph.mlp(features, actor_);
  switch (head_) {
    case Head::kCategorical: graph.set_action(graph.argmax(head)); break;
    case Head::kMultiCategorical: {
      std::vector<std::string> parts;
      int begin = 0;
      for (int64_t n : categorical_parts_) {
        parts.push_back(graph.argmax(graph.slice(head, begin, static_cast<int>(n))));
        begin += static_cast<int>(n);
      }
      graph.set_action(graph.concat(parts));
      break;
    }
    case Head::kBernoulli: graph.set_action(graph.positive(head)); break;
    case Head::kDiagGaussian:
    case Head::kStateDependentNoise: graph.set_action(head); break;
  }
  if (with_value)
    graph.set_value(graph.mlp(
        separate_value_extractor_ ? vf_extractor_.export_to(graph, encoded) : features, critic_));
}

std::string ActorCriticPolicy::export_value(PolicyGraph& graph, const std::string& obs) const {
  const std::string encoded = encoder_.export_to(graph, obs);
  return graph.mlp(separate_value_extractor_ ? vf_extractor_.export_to(graph, encoded)
                                             : extractor_.export_to(graph, encoded),
                   critic_);
}

void ActorCriticPolicy::predict_values(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                       Eigen::RowVectorXf& values) {
  if (separate_value_extractor_) {
    values = critic_.forward(vf_extractor_.forward(encoder_(obs)));
    return;
  }
  values = critic_.forward(features(obs));
}

Eigen::Ref<const Eigen::MatrixXf> ActorCriticPolicy::features(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  return extractor_.forward(encoder_(obs));
}

Eigen::Ref<const Eigen::MatrixXf> ActorCriticPolicy::value_features(
    const Eigen::Ref<const Eigen::MatrixXf>& obs,
    const Eigen::Ref<const Eigen::MatrixXf>& actor_features) {
  if (!separate_value_extractor_) return actor_features;
  // A CNN's input is the observation itself (the encoder passes images through), so the
  // actor's encoding is still valid here.
  return vf_extractor_.forward(encoder_(obs));
}

void ActorCriticPolicy::evaluate_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                         const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                         Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_prob,
                                         Eigen::RowVectorXf& entropy,
                                         const Eigen::MatrixXf* masks) {
  const Eigen::Ref<const Eigen::MatrixXf> features = this->features(obs);
  evaluate_latents(features, value_features(obs, features), actions, values, log_prob, entropy,
                   masks);
}

void ActorCriticPolicy::evaluate_latents(const Eigen::Ref<const Eigen::MatrixXf>& pi_in,
                                         const Eigen::Ref<const Eigen::MatrixXf>& vf_in,
                                         const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                         Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_prob,
                                         Eigen::RowVectorXf& entropy,
                                         const Eigen::MatrixXf* masks) {
  const Eigen::Index n = pi_in.cols();
  values.resize(n);
  log_prob.resize(n);
  entropy.resize(n);
  check_masks(masks);
  actions_ = actions;
  masked_batch_ = masks != nullptr;
  if (masks) masks_ = *masks;
  // Actor and critic are independent: the critic runs on the second core (bit-identical
  // results either way).
  auto actor_part = [&] {
    const Eigen::MatrixXf& head = actor_.forward(pi_in);
    switch (head_) {
      case Head::kCategorical:
        set_logits(categorical_, head, masks);
        action_row_ = actions.row(0);
        score(categorical_, action_row_, log_prob, entropy);
        break;
      case Head::kMultiCategorical:
        set_logits(multi_categorical_, head, masks);
        score(multi_categorical_, actions, log_prob, entropy);
        break;
      case Head::kBernoulli:
        bernoulli_.set_logits(head);
        score(bernoulli_, actions, log_prob, entropy);
        break;
      case Head::kDiagGaussian:
        gaussian_.set(head, log_std_);
        score(gaussian_, actions, log_prob, entropy);
        break;
      case Head::kStateDependentNoise:
        sde_.set(head, actor_.last_hidden());
        score(sde_, actions, log_prob, entropy);
        break;
    }
  };
  auto critic_part = [&] { values = critic_.forward(vf_in); };
  run_pair(n, actor_part, critic_part);
}

void ActorCriticPolicy::backward(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                                 const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                 const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy) {
  const bool learned = extractor_.learned();
  backward_latents(grad_values, grad_log_prob, grad_entropy, learned ? &grad_features_ : nullptr,
                   learned ? &grad_features_critic_ : nullptr);
  if (separate_value_extractor_) {
    extractor_.backward(grad_features_);
    vf_extractor_.backward(grad_features_critic_);
  } else if (learned) {
    // The shared extractor gets both losses' gradients, as autograd sums them.
    grad_features_ += grad_features_critic_;
    extractor_.backward(grad_features_);
  }
}

void ActorCriticPolicy::backward_latents(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                                         const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                         const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                                         Eigen::MatrixXf* grad_pi_in, Eigen::MatrixXf* grad_vf_in) {
  auto actor_part = [&] {
    switch (head_) {
      case Head::kCategorical:
        categorical_.backward(action_row_, grad_log_prob, grad_entropy, grad_head_);
        break;
      case Head::kMultiCategorical:
        multi_categorical_.backward(actions_, grad_log_prob, grad_entropy, grad_head_);
        break;
      case Head::kBernoulli:
        bernoulli_.backward(actions_, grad_log_prob, grad_entropy, grad_head_);
        break;
      case Head::kDiagGaussian:
        gaussian_.backward(actions_, grad_log_prob, grad_entropy, grad_head_, grad_log_std_batch_);
        log_std_grad_ += grad_log_std_batch_;
        break;
      case Head::kStateDependentNoise:
        // Adds to the log_std matrix's gradient; the latent is detached (learn_features false).
        sde_.backward_scored(actions_, grad_log_prob, grad_entropy, grad_head_);
        break;
    }
    if (masked_batch_) mask_logit_gradient(masks_, grad_head_);
    actor_.backward(grad_head_, grad_pi_in);
  };
  auto critic_part = [&] { critic_.backward(grad_values, grad_vf_in); };
  run_pair(grad_values.size(), actor_part, critic_part);
}

void ActorCriticPolicy::run_pair(Eigen::Index batch, const std::function<void()>& actor_part,
                                 const std::function<void()>& critic_part) {
  // Below ~32 samples the hand-off costs more than the halved work.
  if (batch >= 32 && pool_ != nullptr) {
    pool_->run(2, [&](int part) { part == 0 ? actor_part() : critic_part(); });
  } else {
    actor_part();
    critic_part();
  }
}

void ActorCriticPolicy::zero_grad() {
  extractor_.zero_grad();
  vf_extractor_.zero_grad();
  actor_.zero_grad();
  critic_.zero_grad();
  log_std_grad_.setZero();
  if (use_sde()) sde_.zero_grad();
}

std::vector<ParamBlock> ActorCriticPolicy::param_blocks() {
  // SB3's parameter order: the features extractor(s), the towers and heads, log_std.
  std::vector<ParamBlock> blocks;
  for (const ParamBlock& b : extractor_.blocks()) blocks.push_back(b);
  for (const ParamBlock& b : vf_extractor_.blocks()) blocks.push_back(b);
  blocks.push_back(actor_.block());
  blocks.push_back(critic_.block());
  if (head_ == Head::kDiagGaussian)
    blocks.push_back({log_std_.data(), log_std_grad_.data(), log_std_.size()});
  if (use_sde()) blocks.push_back(sde_.block());
  return blocks;
}

double ActorCriticPolicy::mean_std() const {
  if (!gaussian()) return std::nan("");
  // SB3 ppo.py / a2c.py: th.exp(self.policy.log_std).mean(), whatever get_std would say.
  if (use_sde()) return sde_.log_std().array().exp().mean();
  return log_std_.array().exp().mean();
}

// SB3's state_dict names: features_extractor.* when shared; pi_features_extractor.* and
// vf_features_extractor.* when not (SB3 also lists the actor's under features_extractor.*, the
// same module twice; rlrun writes each network once).
void ActorCriticPolicy::save(TensorMap& tensors) const {
  if (separate_value_extractor_) {
    extractor_.save("pi_features_extractor", tensors);
    vf_extractor_.save("vf_features_extractor", tensors);
  } else {
    extractor_.save("features_extractor", tensors);
  }
  save_mlp(actor_, "mlp_extractor.policy_net", "action_net", tensors);
  save_mlp(critic_, "mlp_extractor.value_net", "value_net", tensors);
  if (head_ == Head::kDiagGaussian) tensors["log_std"] = to_tensor(log_std_);
  if (use_sde()) tensors["log_std"] = to_tensor(sde_.log_std());
}

void ActorCriticPolicy::load(const TensorMap& tensors) {
  if (separate_value_extractor_) {
    extractor_.load("pi_features_extractor", tensors);
    vf_extractor_.load("vf_features_extractor", tensors);
  } else {
    extractor_.load("features_extractor", tensors);
  }
  load_mlp(actor_, "mlp_extractor.policy_net", "action_net", tensors);
  load_mlp(critic_, "mlp_extractor.value_net", "value_net", tensors);
  if (head_ == Head::kDiagGaussian) from_tensor(tensors, "log_std", log_std_);
  if (use_sde()) from_tensor(tensors, "log_std", sde_.log_std());
}

}  // namespace rlrun
