#pragma once
// What a network sees of an observation: SB3's preprocess_obs (common/preprocessing.py) followed
// by its FlattenExtractor / CombinedExtractor for vector keys (common/torch_layers.py), on
// rlrun's flat observations (rlrun/space.hpp lays a Dict out as its keys' values in sorted
// order):
//   Box              as it is (flattened); an image divided by 255 with normalize_images
//                    (SB3's is_image_space: 3 dimensions, uint8, bounds 0-255 — preprocess_obs does
//                    it for every policy, MlpPolicy too; a NatureCNN divides its own input)
//   MultiBinary(n)   its n bits as floats
//   Discrete(n)      one-hot of n floats (value - start: SB3 has no start, Gymnasium does)
//   MultiDiscrete    the one-hots of its entries, concatenated (n_0 + n_1 + ... floats)
//   Dict             each key so, in sorted key order, concatenated (CombinedExtractor: one
//                    nn.Flatten per vector key, th.cat in the order of the Dict's keys)
// The encoders have no parameters, so a model of a Dict env has SB3 MultiInputPolicy's tensor
// names (features_extractor.extractors.* are parameter-free Flatten modules).
//
// When the network input is the observation itself (Box, MultiBinary, a Dict of those) the
// encoder is the identity: operator() hands back the caller's matrix, no copy, no cost.
// Used by the policies (PPO, A2C: algos/common/actor_critic_policy.hpp) and by the
// OneHotObservation wrapper.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/space.hpp"

namespace rlrun {

class PolicyGraph;

class ObservationEncoder {
 public:
  ObservationEncoder() = default;
  // normalize_images: SB3's policy keyword (true by default there); off for wrappers and for a
  // policy whose NatureCNN reads the pixels.
  explicit ObservationEncoder(const Space& observation_space, bool normalize_images = false);

  // Floats per observation in (the space's flat_dim) and per network input out (SB3's
  // features_dim).
  int input_dim() const { return input_dim_; }
  int features_dim() const { return features_dim_; }
  // True when the network input is the observation itself.
  bool identity() const { return identity_; }

  // One observation (input_dim floats) -> network input (features_dim floats). Throws
  // std::out_of_range naming the entry (and key) when a Discrete / MultiDiscrete value is
  // not an index of its space.
  void encode_sample(std::span<const float> obs, std::span<float> out) const;
  // The inverse for drawing encoded observations: each one-hot block becomes the value of
  // its largest float; everything else is copied back.
  void decode_sample(std::span<const float> features, std::span<float> obs) const;
  // Column by column; `out` is resized to features_dim x obs.cols() (no allocation when the
  // size is unchanged). Thread-safe (const).
  void encode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& out) const;
  // The same into a block of the right size (features_dim x obs.cols()), e.g. the top rows of
  // a critic's (features; action) input. Copies even when identity(). Thread-safe (const).
  void encode_into(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                   Eigen::Ref<Eigen::MatrixXf> out) const;

  // The network input for a batch of observations (input_dim x batch): `obs` itself when
  // identity(), else the encoding in a workspace that grows to the largest batch seen and is
  // then reused (no allocation). Valid until the next call; one encoder per thread.
  Eigen::Ref<const Eigen::MatrixXf> operator()(const Eigen::Ref<const Eigen::MatrixXf>& obs);

  // Deploying (nn/policy_graph.hpp): the encoding as graph nodes from `obs` (input_dim
  // wide) to the network input (features_dim wide); `obs` itself when identity().
  std::string export_to(PolicyGraph& graph, const std::string& obs) const;

 private:
  // A run of floats copied as they are, or one categorical value turned into a one-hot.
  struct Piece {
    int in = 0;     // first float in the observation
    int out = 0;    // first float in the network input
    int width = 0;  // floats copied, or one-hot width (the category count)
    bool one_hot = false;
    bool image = false;  // copied divided by 255 (normalize_images)
    int64_t start = 0;   // Discrete's start (the value of one-hot slot 0)
    int entry = 0;       // index of the value inside its space, for messages
    int space = 0;       // index into spaces_
  };
  void add_space(const Space& space, const std::string& key, bool normalize_images);
  [[noreturn]] void fail(const Piece& piece, float value) const;

  std::vector<Piece> pieces_;
  std::vector<std::pair<std::string, std::string>> spaces_;  // key ("" = not a Dict), describe()
  int input_dim_ = 0;
  int features_dim_ = 0;
  bool identity_ = true;
  Eigen::MatrixXf workspace_;
};

}  // namespace rlrun
