#include "rlrun/algos/common/q_network.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/nn/activation.hpp"

namespace rlrun {

Mlp make_q_network(int obs_dim, int n_actions, const QNetworkConfig& config, Rng& init_rng) {
  Mlp net(obs_dim, config.net_arch, n_actions, config.activation_fn);
  net.init_torch_default(init_rng);
  return net;
}

void greedy_actions(const Eigen::Ref<const Eigen::MatrixXf>& q, float start,
                    Eigen::MatrixXf& actions) {
  if (actions.rows() != 1 || actions.cols() != q.cols()) actions.resize(1, q.cols());
  for (Eigen::Index j = 0; j < q.cols(); ++j) {
    Eigen::Index best = 0;
    for (Eigen::Index a = 1; a < q.rows(); ++a)
      if (q(a, j) > q(best, j)) best = a;
    actions(0, j) = start + static_cast<float>(best);
  }
}

namespace {
// The output layer's Sequential index: hidden layer l is at 2l, its activation at 2l + 1.
std::string head_name(const Mlp& net, const std::string& name) {
  return name + "." + std::to_string(2 * (net.num_layers() - 1));
}
}  // namespace

void save_q_network(const Mlp& net, const std::string& name, TensorMap& out) {
  save_mlp(net, name, head_name(net, name), out);
}

void load_q_network(Mlp& net, const std::string& name, const TensorMap& in) {
  load_mlp(net, name, head_name(net, name), in);
}

}  // namespace rlrun
