#include "rlrun/algos/sac/sac_actor.hpp"

#include <stdexcept>

namespace rlrun {

SacActor::SacActor(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                   Activation activation)
    : action_dim_(action_dim), net_(obs_dim, net_arch, 2 * action_dim, activation) {}

void SacActor::forward_heads(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  const Eigen::MatrixXf& out = net_.forward(obs);
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
  dist_.sample(rng, actions);
  dist_.log_prob(log_prob);
}

void SacActor::sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                 const Eigen::Ref<const Eigen::MatrixXf>& noise,
                                 Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob) {
  forward_heads(obs);
  actions.resize(action_dim_, obs.cols());
  log_prob.resize(obs.cols());
  dist_.sample_from_noise(noise, actions);
  dist_.log_prob(log_prob);
}

void SacActor::mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions) {
  forward_heads(obs);
  actions.resize(action_dim_, obs.cols());
  dist_.mode(actions);
}

void SacActor::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                        const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob) {
  dist_.backward(grad_actions, grad_log_prob, grad_mean_, grad_log_std_);
  grad_head_.resize(2 * action_dim_, grad_mean_.cols());
  grad_head_.topRows(action_dim_) = grad_mean_;
  grad_head_.bottomRows(action_dim_) = grad_log_std_;
  // No gradient where the raw log_std was clamped (torch's clamp backward).
  SquashedGaussian::clamp_log_std_backward(net_.output().bottomRows(action_dim_),
                                           grad_head_.bottomRows(action_dim_));
  net_.zero_grad_and_backward(grad_head_);
}

void SacActor::save(const std::string& prefix, TensorMap& tensors) const {
  const Mlp& m = net();
  const int last = m.num_layers() - 1;
  for (int l = 0; l < last; ++l) {
    const std::string name = prefix + ".latent_pi." + std::to_string(2 * l);
    tensors[name + ".weight"] = to_tensor(Eigen::MatrixXf(m.weight(l)));
    tensors[name + ".bias"] = to_tensor(Eigen::VectorXf(m.bias(l)));
  }
  tensors[prefix + ".mu.weight"] =
      to_tensor(Eigen::MatrixXf(m.weight(last).topRows(action_dim_)));
  tensors[prefix + ".mu.bias"] = to_tensor(Eigen::VectorXf(m.bias(last).head(action_dim_)));
  tensors[prefix + ".log_std.weight"] =
      to_tensor(Eigen::MatrixXf(m.weight(last).bottomRows(action_dim_)));
  tensors[prefix + ".log_std.bias"] = to_tensor(Eigen::VectorXf(m.bias(last).tail(action_dim_)));
}

void SacActor::load(const std::string& prefix, const TensorMap& tensors) {
  Mlp& m = net();
  const int last = m.num_layers() - 1;
  for (int l = 0; l < last; ++l) {
    const std::string name = prefix + ".latent_pi." + std::to_string(2 * l);
    from_tensor(tensors, name + ".weight", m.weight(l));
    from_tensor(tensors, name + ".bias", m.bias(l));
  }
  from_tensor(tensors, prefix + ".mu.weight", m.weight(last).topRows(action_dim_));
  from_tensor(tensors, prefix + ".mu.bias", m.bias(last).head(action_dim_));
  from_tensor(tensors, prefix + ".log_std.weight", m.weight(last).bottomRows(action_dim_));
  from_tensor(tensors, prefix + ".log_std.bias", m.bias(last).tail(action_dim_));
}

}  // namespace rlrun
