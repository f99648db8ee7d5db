#include "rlrun/algos/crossq/crossq_networks.hpp"

#include <stdexcept>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

CrossQActor::CrossQActor(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                         Activation activation, const CrossQNorm& norm, const SacActorSde& sde,
                         ThreadPool* pool)
    // create_mlp(features_dim, -1, net_arch, pre_linear_modules) + the trailing BatchRenorm.
    : latent_pi_(obs_dim, net_arch, 0, activation, norm.batch_norm, norm.options, pool),
      heads_(latent_pi_.out_dim(), action_dim, {}, activation, sde, pool) {
  heads_.keep_input_gradient(true);
}

void CrossQActor::init(Rng& rng) {
  latent_pi_.init_torch_default(rng);
  heads_.net().init_torch_default(rng);
}

std::vector<ParamBlock> CrossQActor::blocks() {
  std::vector<ParamBlock> out = latent_pi_.blocks();
  out.push_back(heads_.net().block());
  if (use_sde()) out.push_back(heads_.sde().block());
  return out;
}

void CrossQActor::copy_parameters_from(const CrossQActor& other) {
  latent_pi_.copy_state_from(other.latent_pi_);
  heads_.copy_parameters_from(other.heads_);
}

void CrossQActor::sample(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training, Rng& rng,
                         Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob) {
  heads_.sample(latent_pi_.forward(obs, training), rng, actions, log_prob);
}

void CrossQActor::sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training,
                                    const Eigen::Ref<const Eigen::MatrixXf>& noise,
                                    Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob) {
  heads_.sample_from_noise(latent_pi_.forward(obs, training), noise, actions, log_prob);
}

void CrossQActor::mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions) {
  heads_.mode(latent_pi_.forward(obs, false), actions);
}

void CrossQActor::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                           const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob) {
  heads_.backward(grad_actions, grad_log_prob);
  latent_pi_.zero_grad_and_backward(heads_.input_gradient());
}

std::string CrossQActor::export_mode(PolicyGraph& graph, const std::string& features) const {
  const Mlp folded = latent_pi_.folded(&heads_.net());
  return heads_.export_mode_from_output(graph, graph.mlp(features, folded));
}

void CrossQActor::save(const std::string& prefix, TensorMap& tensors) const {
  latent_pi_.save(prefix + ".latent_pi", tensors);
  heads_.save(prefix, tensors);
}

void CrossQActor::load(const std::string& prefix, const TensorMap& tensors) {
  latent_pi_.load(prefix + ".latent_pi", tensors);
  heads_.load(prefix, tensors);
}

CrossQCritic::CrossQCritic(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                           Activation activation, int n_critics, const CrossQNorm& norm,
                           ThreadPool* pool)
    : obs_dim_(obs_dim), pool_(pool) {
  if (n_critics < 1) throw std::invalid_argument("CrossQCritic: n_critics must be >= 1");
  for (int i = 0; i < n_critics; ++i)
    q_.emplace_back(obs_dim + action_dim, net_arch, 1, activation, norm.batch_norm, norm.options,
                    pool);
}

void CrossQCritic::init(Rng& rng) {
  for (BatchRenormMlp& q : q_) q.init_torch_default(rng);
}

void CrossQCritic::forward(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                           const Eigen::Ref<const Eigen::MatrixXf>& actions, bool training) {
  obs_action_.resize(obs.rows() + actions.rows(), obs.cols());
  obs_action_ << obs, actions;  // th.cat([features, actions], dim=1)
  for_each_critic(obs.cols(), [&](int i) { q_[i].forward(obs_action_, training); });
}

int CrossQCritic::argmin(Eigen::Index j) const {
  int arg = 0;
  for (int i = 1; i < n_critics(); ++i)
    if (q_[i].output()(0, j) < q_[arg].output()(0, j)) arg = i;
  return arg;
}

void CrossQCritic::save(const std::string& prefix, TensorMap& tensors) const {
  for (int i = 0; i < n_critics(); ++i) q_[i].save(prefix + ".qf" + std::to_string(i), tensors);
}

void CrossQCritic::load(const std::string& prefix, const TensorMap& tensors) {
  for (int i = 0; i < n_critics(); ++i) q_[i].load(prefix + ".qf" + std::to_string(i), tensors);
}

}  // namespace rlrun
