#include "rlrun/algos/common/features_extractor_net.hpp"

#include <stdexcept>

#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/env/image_space.hpp"
#include "rlrun/env/observation_encoder.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

FeaturesExtractorNet::FeaturesExtractorNet(const FeaturesExtractorSettings& settings,
                                           const Space& observation_space, int encoded_dim,
                                           ThreadPool* pool)
    : out_dim_(encoded_dim) {
  switch (settings.kind) {
    case FeaturesExtractor::kFlatten: return;
    case FeaturesExtractor::kNatureCnn:
      cnns_.emplace_back(require_image_input(observation_space, settings.normalize_images),
                         settings.features_dim, settings.normalize_images);
      cnns_.back().set_thread_pool(pool);
      out_dim_ = settings.features_dim;
      return;
    case FeaturesExtractor::kCombined: build_combined(settings, observation_space, pool); return;
  }
}

std::vector<CombinedKey> combined_extractor_keys(const Space& space) {
  if (space.kind() != SpaceKind::kDict)
    throw std::invalid_argument(
        "CombinedExtractor (SB3's MultiInputPolicy) reads Dict observations, not " +
        space.describe() + ": use FlattenExtractor, or NatureCNN for an image");
  // SB3 CombinedExtractor.__init__: for key, subspace in observation_space.spaces.items(),
  // is_image_space(subspace, normalized_image=False) -> NatureCNN, else nn.Flatten; rlrun's
  // encoding lays the keys out in the same (sorted) order.
  std::vector<CombinedKey> keys;
  for (size_t i = 0; i < space.keys().size(); ++i) {
    const Space& sub = space.subspaces()[i];
    keys.push_back({space.keys()[i], ObservationEncoder(sub).features_dim(),
                    image_input(sub, /*normalize_images=*/true)});
  }
  return keys;
}

void FeaturesExtractorNet::build_combined(const FeaturesExtractorSettings& settings,
                                          const Space& space, ThreadPool* pool) {
  int in = 0, out = 0;
  for (const CombinedKey& k : combined_extractor_keys(space)) {
    Part part;
    part.key = k.key;
    part.in = in;
    part.in_width = k.encoded_width;
    part.out = out;
    part.out_width = k.encoded_width;
    if (k.image) {  // NatureCNN(subspace, features_dim=cnn_output_dim)
      part.cnn = static_cast<int>(cnns_.size());
      cnns_.emplace_back(*k.image, settings.cnn_output_dim, settings.normalize_images);
      cnns_.back().set_thread_pool(pool);
      part.out_width = settings.cnn_output_dim;
    }
    in += part.in_width;
    out += part.out_width;
    parts_.push_back(part);
  }
  out_dim_ = out;
}

void FeaturesExtractorNet::init_torch_default(Rng& rng) {
  for (NatureCnn& cnn : cnns_) cnn.init_torch_default(rng);
}

void FeaturesExtractorNet::init_orthogonal(Rng& rng, float gain) {
  for (NatureCnn& cnn : cnns_) cnn.init_orthogonal(rng, gain);
}

Eigen::Ref<const Eigen::MatrixXf> FeaturesExtractorNet::forward(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  if (cnns_.empty()) return obs;
  if (!combined()) return cnns_.front().forward(obs);
  // SB3 CombinedExtractor.forward: th.cat([extractor(observations[key]) ...], dim=1).
  features_.resize(out_dim_, obs.cols());
  for (const Part& p : parts_) {
    if (p.cnn < 0)
      features_.middleRows(p.out, p.out_width) = obs.middleRows(p.in, p.in_width);
    else
      features_.middleRows(p.out, p.out_width) =
          cnns_[p.cnn].forward(obs.middleRows(p.in, p.in_width));
  }
  return features_;
}

void FeaturesExtractorNet::zero_grad() {
  for (NatureCnn& cnn : cnns_) cnn.zero_grad();
}

void FeaturesExtractorNet::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features) {
  if (!combined()) {
    if (!cnns_.empty()) cnns_.front().backward(grad_features);
    return;
  }
  for (const Part& p : parts_)
    if (p.cnn >= 0) cnns_[p.cnn].backward(grad_features.middleRows(p.out, p.out_width));
}

void FeaturesExtractorNet::zero_grad_and_backward(
    const Eigen::Ref<const Eigen::MatrixXf>& grad_features) {
  zero_grad();
  backward(grad_features);
}

std::vector<ParamBlock> FeaturesExtractorNet::blocks() {
  std::vector<ParamBlock> out;
  for (NatureCnn& cnn : cnns_) out.push_back(cnn.block());
  return out;
}

void FeaturesExtractorNet::copy_parameters_from(const FeaturesExtractorNet& other) {
  for (size_t i = 0; i < cnns_.size(); ++i) cnns_[i].params() = other.cnns_[i].params();
}

std::string FeaturesExtractorNet::export_to(PolicyGraph& graph, const std::string& encoded) const {
  if (cnns_.empty()) return encoded;
  if (!combined()) return graph.nature_cnn(encoded, cnns_.front());
  std::vector<std::string> parts;
  for (const Part& p : parts_) {
    const std::string slice = graph.slice(encoded, p.in, p.in_width);
    parts.push_back(p.cnn < 0 ? slice : graph.nature_cnn(slice, cnns_[p.cnn]));
  }
  return graph.concat(parts);
}

std::string FeaturesExtractorNet::cnn_module(const std::string& module, int i) const {
  if (!combined()) return module;
  for (const Part& p : parts_)
    if (p.cnn == i) return module + ".extractors." + p.key;
  return module;
}

void FeaturesExtractorNet::save(const std::string& module, TensorMap& tensors) const {
  for (int i = 0; i < num_cnns(); ++i) cnns_[i].save(cnn_module(module, i), tensors);
}

void FeaturesExtractorNet::load(const std::string& module, const TensorMap& tensors) {
  for (int i = 0; i < num_cnns(); ++i) cnns_[i].load(cnn_module(module, i), tensors);
}

void polyak_update(const FeaturesExtractorNet& source, FeaturesExtractorNet& target, float tau) {
  for (int i = 0; i < source.num_cnns(); ++i)
    polyak_update(source.cnn(i).params(), target.cnn(i).params(), tau);
}

}  // namespace rlrun
