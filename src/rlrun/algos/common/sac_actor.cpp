#include "rlrun/algos/common/sac_actor.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/training_state.hpp"

namespace rlrun {

SacActor::SacActor(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, const SacActorSde& sde, ThreadPool* pool)
    : SacActor(FeaturesExtractorNet(obs_dim), action_dim, net_arch, activation, sde, pool) {}

SacActor::SacActor(FeaturesExtractorNet extractor, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, const SacActorSde& sde, ThreadPool* pool)
    : action_dim_(action_dim),
      extractor_(std::move(extractor)),
      net_(extractor_.out_dim(), net_arch, sde.use_sde ? action_dim : 2 * action_dim, activation,
           pool),
      sde_options_(sde) {
  if (sde.use_sde) {
    // SB3 Actor: StateDependentNoiseDistribution(action_dim, full_std, use_expln,
    // learn_features=True, squash_output=True), proba_distribution_net on latent_pi's width.
    StateDependentNoiseOptions options;
    options.full_std = sde.full_std;
    options.use_expln = sde.use_expln;
    options.squash_output = true;
    options.learn_features = true;
    const Mlp& m = net_.net();
    sde_ =
        StateDependentNoise(m.layer_in(m.num_layers() - 1), action_dim, sde.log_std_init, options);
  }
}

void SacActor::copy_parameters_from(const SacActor& other) {
  extractor_.copy_parameters_from(other.extractor_);
  net().params() = other.net().params();
  if (use_sde()) sde_.log_std() = other.sde_.log_std();
}

void SacActor::reset_noise(Rng& rng, int batch_size) {
  if (!use_sde()) throw std::logic_error("reset_noise() is only available when using gSDE");
  sde_.sample_weights(rng, batch_size);
}

void SacActor::write_state(StateWriter out) const {
  if (use_sde()) write_sde(out, sde_);
}

void SacActor::read_state(const StateReader& in) {
  if (use_sde()) read_sde(in, sde_);
}

void SacActor::forward_heads(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  const Eigen::MatrixXf& out = net_.forward(extractor_.forward(obs));
  if (use_sde()) {
    // SB3 Actor: mu = Hardtanh(-clip_mean, clip_mean)(Linear(latent_pi)); latent_sde = latent_pi.
    const float c = sde_options_.clip_mean;
    if (c > 0.0f)
      mu_ = out.cwiseMax(-c).cwiseMin(c);
    else
      mu_ = out;
    sde_.set(mu_, net_.last_hidden());
    return;
  }
  log_std_.resize(action_dim_, out.cols());
  // SB3 Actor.get_action_dist_params: th.clamp(log_std, LOG_STD_MIN, LOG_STD_MAX).
  SquashedGaussian::clamp_log_std(out.bottomRows(action_dim_), log_std_);
  dist_.set(out.topRows(action_dim_), log_std_);
}

void SacActor::sample(const Eigen::Ref<const Eigen::MatrixXf>& obs, Rng& rng,
                      Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob) {
  forward_heads(obs);
  actions.resize(action_dim_, obs.cols());
  log_prob.resize(obs.cols());
  if (use_sde()) {
    // log_prob_from_params: the squashed sample, then log_prob of that action.
    sde_.sample(actions);
    sde_.log_prob(actions, log_prob);
    return;
  }
  dist_.sample(rng, actions);
  dist_.log_prob(log_prob);
}

void SacActor::sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                 const Eigen::Ref<const Eigen::MatrixXf>& noise,
                                 Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob) {
  if (use_sde())
    throw std::logic_error("SacActor::sample_from_noise: gSDE draws from its exploration matrix");
  forward_heads(obs);
  actions.resize(action_dim_, obs.cols());
  log_prob.resize(obs.cols());
  dist_.sample_from_noise(noise, actions);
  dist_.log_prob(log_prob);
}

void SacActor::mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions) {
  forward_heads(obs);
  actions.resize(action_dim_, obs.cols());
  if (use_sde())
    sde_.mode(actions);
  else
    dist_.mode(actions);
}

std::string SacActor::export_mode(PolicyGraph& graph, const std::string& features) const {
  return export_mode_from_output(graph, graph.mlp(features, net_.net()));
}

std::string SacActor::export_mode_from_output(PolicyGraph& graph,
                                              const std::string& net_output) const {
  std::string mean = net_output;
  if (use_sde()) {
    const float c = sde_options_.clip_mean;
    if (c > 0.0f)
      mean = graph.clamp(mean, Eigen::VectorXf::Constant(action_dim_, -c),
                         Eigen::VectorXf::Constant(action_dim_, c));
  } else {
    mean = graph.slice(mean, 0, action_dim_);  // the log_std rows do not matter for the mode
  }
  return graph.activation(mean, Activation::kTanh);
}

void SacActor::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                        const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob) {
  if (use_sde()) {
    sde_.zero_grad();
    sde_.backward_sampled(grad_actions, grad_log_prob, grad_mean_, &grad_latent_);
    // nn.Hardtanh's backward: no gradient where the raw mu was at or beyond +-clip_mean.
    const float c = sde_options_.clip_mean;
    if (c > 0.0f) {
      const auto raw = net_.output().array();
      grad_mean_ = (raw > -c && raw < c).select(grad_mean_.array(), 0.0f).matrix();
    }
    backward_network(grad_mean_, &grad_latent_);
    return;
  }
  dist_.backward(grad_actions, grad_log_prob, grad_mean_, grad_log_std_);
  grad_head_.resize(2 * action_dim_, grad_mean_.cols());
  grad_head_.topRows(action_dim_) = grad_mean_;
  grad_head_.bottomRows(action_dim_) = grad_log_std_;
  // No gradient where the raw log_std was clamped (torch's clamp backward).
  SquashedGaussian::clamp_log_std_backward(net_.output().bottomRows(action_dim_),
                                           grad_head_.bottomRows(action_dim_));
  backward_network(grad_head_, nullptr);
}

void SacActor::backward_network(const Eigen::MatrixXf& grad_out,
                                const Eigen::MatrixXf* grad_latent) {
  if (!extractor_.learned() && !keep_input_gradient_) {
    net_.zero_grad_and_backward(grad_out, grad_latent);
    return;
  }
  net_.zero_grad_and_backward(grad_out, grad_latent, &grad_features_);
  // Without hidden layers gSDE's latent_pi is the features themselves: its gradient goes to
  // the extractor directly (the network ignores it, having no hidden layer to send it to).
  if (grad_latent && net_.net().num_layers() == 1) grad_features_ += *grad_latent;
  if (extractor_.learned()) extractor_.zero_grad_and_backward(grad_features_);
}

std::string SacActor::mu_name(const std::string& prefix) const {
  // With clip_mean, SB3's mu is nn.Sequential(nn.Linear, nn.Hardtanh): the Linear is `mu.0`.
  return prefix + (use_sde() && sde_options_.clip_mean > 0.0f ? ".mu.0" : ".mu");
}

void SacActor::save(const std::string& prefix, TensorMap& tensors) const {
  extractor_.save(prefix + ".features_extractor", tensors);
  const Mlp& m = net();
  const int last = m.num_layers() - 1;
  for (int l = 0; l < last; ++l) {
    const std::string name = prefix + ".latent_pi." + std::to_string(2 * l);
    tensors[name + ".weight"] = to_tensor(Eigen::MatrixXf(m.weight(l)));
    tensors[name + ".bias"] = to_tensor(Eigen::VectorXf(m.bias(l)));
  }
  const std::string mu = mu_name(prefix);
  tensors[mu + ".weight"] = to_tensor(Eigen::MatrixXf(m.weight(last).topRows(action_dim_)));
  tensors[mu + ".bias"] = to_tensor(Eigen::VectorXf(m.bias(last).head(action_dim_)));
  if (use_sde()) {
    tensors[prefix + ".log_std"] = to_tensor(sde_.log_std());
    return;
  }
  tensors[prefix + ".log_std.weight"] =
      to_tensor(Eigen::MatrixXf(m.weight(last).bottomRows(action_dim_)));
  tensors[prefix + ".log_std.bias"] = to_tensor(Eigen::VectorXf(m.bias(last).tail(action_dim_)));
}

void SacActor::load(const std::string& prefix, const TensorMap& tensors) {
  extractor_.load(prefix + ".features_extractor", tensors);
  Mlp& m = net();
  const int last = m.num_layers() - 1;
  for (int l = 0; l < last; ++l) {
    const std::string name = prefix + ".latent_pi." + std::to_string(2 * l);
    from_tensor(tensors, name + ".weight", m.weight(l));
    from_tensor(tensors, name + ".bias", m.bias(l));
  }
  const std::string mu = mu_name(prefix);
  from_tensor(tensors, mu + ".weight", m.weight(last).topRows(action_dim_));
  from_tensor(tensors, mu + ".bias", m.bias(last).head(action_dim_));
  if (use_sde()) {
    from_tensor(tensors, prefix + ".log_std", sde_.log_std());
    return;
  }
  from_tensor(tensors, prefix + ".log_std.weight", m.weight(last).bottomRows(action_dim_));
  from_tensor(tensors, prefix + ".log_std.bias", m.bias(last).tail(action_dim_));
}

}  // namespace rlrun
