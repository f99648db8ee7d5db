#pragma once
// `policy.features_extractor_class` as a config value: what turns an observation into the
// features the actor and critic heads read (SB3 common/torch_layers.py):
//   FlattenExtractor  the observation itself, flattened (one-hots for discrete values, a
//                     Dict's keys side by side: env/observation_encoder.hpp) — SB3's MlpPolicy
//                     and MultiInputPolicy
//   NatureCNN         SB3's CnnPolicy: the convolutions of nn/nature_cnn.hpp on an image
//   CombinedExtractor SB3's MultiInputPolicy on a Dict: a NatureCNN of cnn_output_dim (256)
//                     features for each image key, the other keys flattened, side by side
// SB3 names the policy class instead (PPO("CnnPolicy", ...)); rl-zoo's `policy: CnnPolicy`
// imports as NatureCNN.
#include <yaml-cpp/yaml.h>

#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_fields.hpp"

namespace rlrun {

enum class FeaturesExtractor { kFlatten, kNatureCnn, kCombined };

// SB3 policy_kwargs that choose and shape the extractor.
struct FeaturesExtractorSettings {
  FeaturesExtractor kind = FeaturesExtractor::kFlatten;
  int features_dim = 512;    // NatureCNN's output width
  int cnn_output_dim = 256;  // CombinedExtractor: each image key's NatureCNN width
  bool normalize_images = true;
};

inline constexpr const char* kFeaturesExtractorDoc =
    "FlattenExtractor (SB3's MlpPolicy), NatureCNN (SB3's CnnPolicy, for image observations; "
    "SB3's CnnPolicy has net_arch [] for PPO, A2C and DQN, [256, 256] for SAC, TD3, DDPG and "
    "TQC) or CombinedExtractor (SB3's MultiInputPolicy: a Dict's image keys through a NatureCNN "
    "each, its other keys flattened)";

inline constexpr const char* kCnnOutputDimDoc =
    "CombinedExtractor: features of each image key's NatureCNN (SB3 features_extractor_kwargs: "
    "cnn_output_dim)";

inline constexpr const char* kFeaturesDimDoc =
    "NatureCNN's output width (SB3 features_extractor_kwargs: features_dim)";

inline constexpr const char* kOffPolicyShareFeaturesExtractorDoc =
    "false (SB3's off-policy default): the actor and the critic each have a features extractor; "
    "true: the critic reads the actor's, which only the actor loss trains";

inline constexpr const char* kNormalizeImagesDoc =
    "divide image observations (a 3-D uint8 Box of 0-255) by 255 before the networks, NatureCNN or "
    "flatten (SB3 normalize_images)";

// The extractor's keys of a policy config, listed as each policy lists them.
template <class V>
void visit_features_extractor(V& v, FeaturesExtractor& kind, int& features_dim,
                              int& cnn_output_dim) {
  v("features_extractor_class", kind, kFeaturesExtractorDoc);
  v("features_dim", features_dim, kFeaturesDimDoc, in_range(1, 65536));
  v("cnn_output_dim", cnn_output_dim, kCnnOutputDimDoc, in_range(1, 65536));
}

// Whether the observation encoder divides images by 255 (SB3 preprocess_obs): only before a
// flatten extractor; a NatureCNN divides its own input (so do CombinedExtractor's).
inline bool encoder_normalizes_images(FeaturesExtractor extractor, bool normalize_images) {
  return extractor == FeaturesExtractor::kFlatten && normalize_images;
}

inline const char* features_extractor_name(FeaturesExtractor f) {
  switch (f) {
    case FeaturesExtractor::kNatureCnn: return "NatureCNN";
    case FeaturesExtractor::kCombined: return "CombinedExtractor";
    case FeaturesExtractor::kFlatten: break;
  }
  return "FlattenExtractor";
}

inline void decode(const ConfigNode& n, FeaturesExtractor& out) {
  const std::string name = n.as_string();
  if (name == "FlattenExtractor" || name == "MlpPolicy") {
    out = FeaturesExtractor::kFlatten;
    return;
  }
  if (name == "NatureCNN" || name == "CnnPolicy") {
    out = FeaturesExtractor::kNatureCnn;
    return;
  }
  if (name == "CombinedExtractor" || name == "MultiInputPolicy") {
    out = FeaturesExtractor::kCombined;
    return;
  }
  n.fail("unknown features extractor '" + name + "'" +
         did_you_mean(name, {"FlattenExtractor", "NatureCNN", "CombinedExtractor"}) +
         "; valid: FlattenExtractor, NatureCNN, CombinedExtractor");
}

inline YAML::Node encode(FeaturesExtractor f) {
  return YAML::Node(std::string(features_extractor_name(f)));
}

}  // namespace rlrun
