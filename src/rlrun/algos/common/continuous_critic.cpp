#include "rlrun/algos/common/continuous_critic.hpp"

#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/polyak.hpp"

namespace rlrun {

ContinuousCritic::ContinuousCritic(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                                   Activation activation, int n_critics, int n_outputs,
                                   ThreadPool* pool)
    : ContinuousCritic(FeaturesExtractorNet(obs_dim), action_dim, net_arch, activation, n_critics,
                       n_outputs, pool) {}

ContinuousCritic::ContinuousCritic(FeaturesExtractorNet extractor, int action_dim,
                                   const std::vector<int>& net_arch, Activation activation,
                                   int n_critics, int n_outputs, ThreadPool* pool)
    : obs_dim_(extractor.out_dim()), pool_(pool), extractor_(std::move(extractor)) {
  if (n_critics < 1) throw std::invalid_argument("ContinuousCritic: n_critics must be >= 1");
  if (n_outputs < 1) throw std::invalid_argument("ContinuousCritic: n_outputs must be >= 1");
  for (int i = 0; i < n_critics; ++i)
    q_.emplace_back(obs_dim_ + action_dim, net_arch, n_outputs, activation, pool);
  if (extractor_.learned()) grad_inputs_.resize(n_critics);
}

void ContinuousCritic::init(Rng& rng) {
  for (SplitMlp& q : q_) q.net().init_torch_default(rng);
}

void ContinuousCritic::concat_input(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                    const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  const Eigen::Ref<const Eigen::MatrixXf> features = features_extractor().forward(obs);
  obs_action_.resize(features.rows() + actions.rows(), features.cols());
  obs_action_ << features, actions;
}

void ContinuousCritic::forward(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                               const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  concat_input(obs, actions);  // th.cat([features, actions], dim=1)
  for_each_critic(obs.cols(), [&](int i) { q_[i].forward(obs_action_); });
}

void ContinuousCritic::zero_grad_and_backward(int i,
                                              const Eigen::Ref<const Eigen::MatrixXf>& grad_q) {
  q_[i].zero_grad_and_backward(grad_q, nullptr, extractor_.learned() ? &grad_inputs_[i] : nullptr);
}

void ContinuousCritic::share_features_extractor(FeaturesExtractorNet& other) {
  if (other.out_dim() != obs_dim_)
    throw std::invalid_argument("ContinuousCritic: a shared extractor must give " +
                                std::to_string(obs_dim_) + " features");
  shared_ = &other;
  extractor_ = FeaturesExtractorNet(obs_dim_);  // no parameters of its own
  grad_inputs_.clear();
}

void ContinuousCritic::own_features_extractor_copy() {
  if (!shared_) return;
  extractor_ = *shared_;
  shared_ = nullptr;
  if (extractor_.learned()) grad_inputs_.resize(n_critics());
}

void ContinuousCritic::backward_features_extractor() {
  if (!extractor_.learned()) return;
  grad_features_ = grad_inputs_[0].topRows(obs_dim_);
  for (int i = 1; i < n_critics(); ++i) grad_features_ += grad_inputs_[i].topRows(obs_dim_);
  extractor_.zero_grad_and_backward(grad_features_);
}

int ContinuousCritic::argmin(Eigen::Index j) const {
  int arg = 0;
  for (int i = 1; i < n_critics(); ++i)
    if (q_[i].output()(0, j) < q_[arg].output()(0, j)) arg = i;
  return arg;
}

const Eigen::MatrixXf& ContinuousCritic::q1_forward(
    const Eigen::Ref<const Eigen::MatrixXf>& obs,
    const Eigen::Ref<const Eigen::MatrixXf>& actions) {
  concat_input(obs, actions);
  return q_.front().forward(obs_action_);
}

void ContinuousCritic::action_gradient(int i, const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                                       Eigen::MatrixXf& grad_actions) {
  q_[i].backward_input(grad_q, grad_actions, obs_dim_);
}

void ContinuousCritic::save(const std::string& prefix, TensorMap& tensors) const {
  features_extractor().save(prefix + ".features_extractor", tensors);
  for (int i = 0; i < n_critics(); ++i) {
    const Mlp& net = q_[i].net();
    const std::string name = prefix + ".qf" + std::to_string(i);
    save_mlp(net, name, name + "." + std::to_string(2 * (net.num_layers() - 1)), tensors);
  }
}

void ContinuousCritic::load(const std::string& prefix, const TensorMap& tensors) {
  extractor_.load(prefix + ".features_extractor", tensors);
  for (int i = 0; i < n_critics(); ++i) {
    Mlp& net = q_[i].net();
    const std::string name = prefix + ".qf" + std::to_string(i);
    load_mlp(net, name, name + "." + std::to_string(2 * (net.num_layers() - 1)), tensors);
  }
}

void polyak_update(const ContinuousCritic& critic, ContinuousCritic& target, float tau) {
  polyak_update(critic.features_extractor(), target.features_extractor(), tau);
  for (int i = 0; i < critic.n_critics(); ++i)
    polyak_update(critic.q(i).params(), target.q(i).params(), tau);
}

}  // namespace rlrun
