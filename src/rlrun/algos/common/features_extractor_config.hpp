#pragma once
// `policy.features_extractor_class` as a config value: what turns an observation into the
// features the actor and critic heads read (SB3 common/torch_layers.py):
//   FlattenExtractor  the observation itself, flattened (one-hots for discrete values, a
//                     Dict's keys side by side: env/observation_encoder.hpp) — SB3's MlpPolicy
//                     and MultiInputPolicy
//   NatureCNN         SB3's CnnPolicy: the convolutions of nn/nature_cnn.hpp on an image
// SB3 names the policy class instead (PPO("CnnPolicy", ...)); rl-zoo's `policy: CnnPolicy`
// imports as NatureCNN.
#include <yaml-cpp/yaml.h>

#include <string>

#include "rlrun/core/config_fields.hpp"

namespace rlrun {

enum class FeaturesExtractor { kFlatten, kNatureCnn };

inline constexpr const char* kFeaturesExtractorDoc =
    "FlattenExtractor (SB3's MlpPolicy / MultiInputPolicy) or NatureCNN (SB3's CnnPolicy, for "
    "image observations; SB3's CnnPolicy has net_arch [] for PPO, A2C and DQN, [256, 256] for "
    "SAC, TD3, DDPG and TQC)";

inline constexpr const char* kFeaturesDimDoc =
    "NatureCNN's output width (SB3 features_extractor_kwargs: features_dim)";

inline constexpr const char* kOffPolicyShareFeaturesExtractorDoc =
    "SB3's off-policy default false: the actor and the critic each have a NatureCNN (true is not "
    "supported yet)";

inline constexpr const char* kNormalizeImagesDoc =
    "divide image observations (a 3-D uint8 Box of 0-255) by 255 before the networks, NatureCNN or "
    "flatten (SB3 normalize_images)";

// Whether the observation encoder divides images by 255 (SB3 preprocess_obs): only before a
// flatten extractor; a NatureCNN divides its own input.
inline bool encoder_normalizes_images(FeaturesExtractor extractor, bool normalize_images) {
  return extractor == FeaturesExtractor::kFlatten && normalize_images;
}

inline const char* features_extractor_name(FeaturesExtractor f) {
  return f == FeaturesExtractor::kNatureCnn ? "NatureCNN" : "FlattenExtractor";
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
  n.fail("unknown features extractor '" + name + "'" +
         did_you_mean(name, {"FlattenExtractor", "NatureCNN"}) +
         "; valid: FlattenExtractor, NatureCNN");
}

inline YAML::Node encode(FeaturesExtractor f) {
  return YAML::Node(std::string(features_extractor_name(f)));
}

}  // namespace rlrun
