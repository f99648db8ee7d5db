#pragma once
// The features extractor module of one of SB3's networks (BaseModel.features_extractor,
// common/torch_layers.py): what an actor, a critic or their targets run on the observation
// before their MLP heads. FlattenExtractor has no parameters: the features are the observation
// encoder's output itself. NatureCNN (CnnPolicy) is a network of its own (nn/nature_cnn.hpp),
// trained by the loss of the module it belongs to.
//
// SB3's off-policy policies (sac/policies.py, td3/policies.py, sb3-contrib tqc/policies.py;
// share_features_extractor=False, their default) give the actor, the critic and each target a
// NatureCNN of its own: the critic's is trained by the critic loss (all n_critics Q-networks
// read its features: common/policies.py ContinuousCritic), the actor's by the actor loss, and the
// targets' follow by Polyak averaging like the rest of the target network. So SacActor,
// Td3Actor and ContinuousCritic each hold one of these, and their copies, targets and
// save names (`actor.features_extractor.cnn.0.weight`, `critic_target.features_extractor...`)
// come with them.
#include <Eigen/Core>
#include <string>

#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class PolicyGraph;

// SB3 policy_kwargs that choose and shape the extractor.
struct FeaturesExtractorSettings {
  FeaturesExtractor kind = FeaturesExtractor::kFlatten;
  int features_dim = 512;  // NatureCNN's output width
  bool normalize_images = true;
};

class FeaturesExtractorNet {
 public:
  // A flatten extractor of `dim` features (the observation encoder's width).
  explicit FeaturesExtractorNet(int dim = 0) : out_dim_(dim) {}
  // A NatureCNN reading observation_space's image (require_image_input: SB3's is_image_space
  // rules, std::invalid_argument with its message); parameters start at zero.
  FeaturesExtractorNet(const FeaturesExtractorSettings& settings, const Space& observation_space,
                       int encoded_dim, ThreadPool* pool);

  // Whether it has parameters to learn (a NatureCNN).
  bool learned() const { return learned_; }
  // Features per observation: the heads' input width.
  int out_dim() const { return out_dim_; }
  const NatureCnn& cnn() const { return cnn_; }
  NatureCnn& cnn() { return cnn_; }

  // torch's default Conv2d / Linear init (SB3 never applies ortho init to off-policy
  // extractors); nothing for a flatten extractor.
  void init_torch_default(Rng& rng);

  // features (out_dim x n) of the encoded observations obs: obs itself when flattening (no
  // copy), else the CNN's output, kept for backward until the next forward.
  Eigen::Ref<const Eigen::MatrixXf> forward(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // optimizer.zero_grad(); features.backward(grad_features) for the last forward: grads()
  // becomes the parameters' gradient. Nothing for a flatten extractor.
  void zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features);

  // The parameters and their gradient (empty for a flatten extractor).
  ParamBlock block() { return learned_ ? cnn_.block() : ParamBlock{nullptr, nullptr, 0}; }
  // The acting copy's refresh (same shapes, no allocation).
  void copy_parameters_from(const FeaturesExtractorNet& other);

  // Deploying (nn/policy_graph.hpp): forward() as graph nodes from the encoded observation.
  std::string export_to(PolicyGraph& graph, const std::string& encoded) const;

  // torch state_dict entries <prefix>.features_extractor.* (none for a flatten extractor).
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  bool learned_ = false;
  int out_dim_ = 0;
  NatureCnn cnn_;
};

// polyak_update(source.parameters(), target.parameters(), tau) of the extractor's part.
void polyak_update(const FeaturesExtractorNet& source, FeaturesExtractorNet& target, float tau);

}  // namespace rlrun
