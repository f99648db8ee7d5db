#pragma once
// SB3's QNetwork (stable_baselines3/dqn/policies.py): the features of the observation through
// create_mlp(features_dim, n_actions, net_arch, activation_fn) -> one Q-value per action.
// Default net_arch [64, 64] and nn.ReLU. The features are the flattened observation (MlpPolicy)
// or a NatureCNN's (CnnPolicy: `features_extractor_class: NatureCNN`, for which SB3's default
// net_arch is [] — write it, as for PPO). SB3 never calls init_weights on it, so the layers,
// convolutions included, keep torch's default init.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

struct QNetworkConfig {
  std::vector<int> net_arch = {64, 64};          // hidden layer sizes
  Activation activation_fn = Activation::kReLU;  // SB3 QNetwork default nn.ReLU
  // SB3 policy_kwargs: features_extractor_class (and features_extractor_kwargs' features_dim),
  // normalize_images. The online and target networks have a NatureCNN each (make_q_net).
  FeaturesExtractor features_extractor_class = FeaturesExtractor::kFlatten;
  int features_dim = 512;
  int cnn_output_dim = 256;
  bool normalize_images = true;

  FeaturesExtractorSettings extractor() const {
    return {features_extractor_class, features_dim, cnn_output_dim, normalize_images};
  }

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, "hidden layer sizes of the Q-network", layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    visit_features_extractor(v, features_extractor_class, features_dim, cnn_output_dim);
    v("normalize_images", normalize_images, kNormalizeImagesDoc);
  }
};

// obs_dim -> net_arch -> n_actions with torch's default Linear init from rng. Throws
// std::invalid_argument for a bad size.
Mlp make_q_network(int obs_dim, int n_actions, const QNetworkConfig& config, Rng& init_rng);

// Column-wise argmax of q (n_actions x batch) into actions (1 x batch) as floats, offset by
// `start` (Discrete(n, start)). Ties go to the lowest index, as torch.argmax.
void greedy_actions(const Eigen::Ref<const Eigen::MatrixXf>& q, float start,
                    Eigen::MatrixXf& actions);

// SB3 state_dict names, without the policy prefix: `<name>.0.weight`, `<name>.2.weight`, ...
// (torch Sequential indices skip the activations), the output layer included.
void save_q_network(const Mlp& net, const std::string& name, TensorMap& out);
void load_q_network(Mlp& net, const std::string& name, const TensorMap& in);

}  // namespace rlrun
