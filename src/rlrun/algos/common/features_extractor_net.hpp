#pragma once
// The features extractor module of one of SB3's networks (BaseModel.features_extractor,
// common/torch_layers.py): what an actor, a critic, a Q-network or their targets run on the
// encoded observation (env/observation_encoder.hpp) before their MLP heads.
//   FlattenExtractor   no parameters: the features are the encoded observation itself
//   NatureCNN          SB3's CnnPolicy: one network on an image (nn/nature_cnn.hpp)
//   CombinedExtractor  SB3's MultiInputPolicy on a Dict: each key an image to SB3
//                      (is_image_space with normalized_image=False: a uint8 Box of three
//                      dimensions, 0-255) through a NatureCNN of its own with cnn_output_dim
//                      features, every other key flattened, th.cat in the Dict's key order
// The networks are trained by the loss of the module that owns the extractor.
//
// SB3's off-policy policies (sac/policies.py, td3/policies.py, sb3-contrib tqc/policies.py;
// share_features_extractor=False, their default) give the actor, the critic and each target an
// extractor of its own: the critic's is trained by the critic loss (all n_critics Q-networks
// read its features: common/policies.py ContinuousCritic), the actor's by the actor loss, and the
// targets' follow by Polyak averaging like the rest of the target network. So SacActor,
// Td3Actor and ContinuousCritic each hold one of these, and their copies, targets and save names
// (`actor.features_extractor.cnn.0.weight`, `critic_target.features_extractor...`) come with
// them. PPO/A2C (ActorCriticPolicy) and DQN hold theirs the same way.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class PolicyGraph;

// SB3 CombinedExtractor's reading of a Dict, key by key in the Dict's order: the key's width in
// the encoded observation and, for a key that is an image to SB3 (is_image_space with
// normalized_image=False: a uint8 Box of three dimensions, 0-255), the image its NatureCNN
// reads. std::invalid_argument (SB3's reason) for a space that is not a Dict. Allocates no
// network: the config checks size the CNNs from it before any is made.
struct CombinedKey {
  std::string key;
  int encoded_width = 0;
  std::optional<ImageInput> image;
};
std::vector<CombinedKey> combined_extractor_keys(const Space& space);

class FeaturesExtractorNet {
 public:
  // A flatten extractor of `dim` features (the observation encoder's width).
  explicit FeaturesExtractorNet(int dim = 0) : out_dim_(dim) {}
  // The extractor `settings` names for observation_space, whose encoding is `encoded_dim`
  // floats wide. NatureCNN: require_image_input's rules (SB3's message, std::invalid_argument);
  // CombinedExtractor: a Dict (std::invalid_argument otherwise). Parameters start at zero.
  FeaturesExtractorNet(const FeaturesExtractorSettings& settings, const Space& observation_space,
                       int encoded_dim, ThreadPool* pool);

  // Whether it has parameters to learn (at least one NatureCNN).
  bool learned() const { return !cnns_.empty(); }
  // Features per observation: the heads' input width.
  int out_dim() const { return out_dim_; }
  // The NatureCNNs, in the Dict's key order for a CombinedExtractor.
  int num_cnns() const { return static_cast<int>(cnns_.size()); }
  const NatureCnn& cnn(int i = 0) const { return cnns_[i]; }
  NatureCnn& cnn(int i = 0) { return cnns_[i]; }
  // Batches split over the pool's threads (null: the calling thread); never changes a result.
  void set_thread_pool(ThreadPool* pool) {
    for (NatureCnn& c : cnns_) c.set_thread_pool(pool);
  }

  // torch's default Conv2d / Linear init (SB3's off-policy extractors, and on-policy ones with
  // ortho_init false); SB3's orthogonal init with `gain` (ActorCriticPolicy's ortho_init),
  // network by network in key order.
  void init_torch_default(Rng& rng);
  void init_orthogonal(Rng& rng, float gain);

  // features (out_dim x n) of the encoded observations obs: obs itself when flattening (no
  // copy), else the networks' outputs, kept for backward until the next forward.
  Eigen::Ref<const Eigen::MatrixXf> forward(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // Adds dL/d(parameters) of the last forward for dL/d(features) (out_dim x n) to grads();
  // zero_grad_and_backward zeroes first (optimizer.zero_grad(); loss.backward()). Nothing for
  // a flatten extractor.
  void zero_grad();
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features);
  void zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features);

  // Each network's parameters and gradient (none for a flatten extractor).
  std::vector<ParamBlock> blocks();
  // The acting copy's refresh (same shapes, no allocation).
  void copy_parameters_from(const FeaturesExtractorNet& other);

  // Deploying (nn/policy_graph.hpp): forward() as graph nodes from the encoded observation.
  std::string export_to(PolicyGraph& graph, const std::string& encoded) const;

  // torch state_dict entries of the module named `module` (e.g. "actor.features_extractor"):
  // <module>.cnn.0.weight, ... for a NatureCNN, <module>.extractors.<key>.cnn.0.weight, ... for
  // a CombinedExtractor's image keys; none for a flatten extractor.
  void save(const std::string& module, TensorMap& tensors) const;
  void load(const std::string& module, const TensorMap& tensors);

 private:
  // A run of the encoded observation and where it goes in the features: through cnns_[cnn], or
  // copied (cnn < 0).
  struct Part {
    int in = 0, in_width = 0, out = 0, out_width = 0;
    int cnn = -1;
    std::string key;
  };
  void build_combined(const FeaturesExtractorSettings& settings, const Space& observation_space,
                      ThreadPool* pool);
  // A CombinedExtractor with at least one image key (its features are assembled from parts).
  bool combined() const { return !parts_.empty() && !cnns_.empty(); }
  std::string cnn_module(const std::string& module, int i) const;

  int out_dim_ = 0;
  std::vector<NatureCnn> cnns_;
  std::vector<Part> parts_;
  Eigen::MatrixXf features_;  // a CombinedExtractor's output
};

// polyak_update(source.parameters(), target.parameters(), tau) of the extractor's part.
void polyak_update(const FeaturesExtractorNet& source, FeaturesExtractorNet& target, float tau);

}  // namespace rlrun
