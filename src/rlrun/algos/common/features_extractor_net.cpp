#include "rlrun/algos/common/features_extractor_net.hpp"

#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/env/image_space.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

FeaturesExtractorNet::FeaturesExtractorNet(const FeaturesExtractorSettings& settings,
                                           const Space& observation_space, int encoded_dim,
                                           ThreadPool* pool)
    : out_dim_(encoded_dim) {
  if (settings.kind != FeaturesExtractor::kNatureCnn) return;
  learned_ = true;
  cnn_ = NatureCnn(require_image_input(observation_space, settings.normalize_images),
                   settings.features_dim, settings.normalize_images);
  cnn_.set_thread_pool(pool);
  out_dim_ = settings.features_dim;
}

void FeaturesExtractorNet::init_torch_default(Rng& rng) {
  if (learned_) cnn_.init_torch_default(rng);
}

Eigen::Ref<const Eigen::MatrixXf> FeaturesExtractorNet::forward(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  if (!learned_) return obs;
  return cnn_.forward(obs);
}

void FeaturesExtractorNet::zero_grad_and_backward(
    const Eigen::Ref<const Eigen::MatrixXf>& grad_features) {
  if (!learned_) return;
  cnn_.zero_grad();
  cnn_.backward(grad_features);
}

void FeaturesExtractorNet::copy_parameters_from(const FeaturesExtractorNet& other) {
  if (learned_) cnn_.params() = other.cnn_.params();
}

void FeaturesExtractorNet::save(const std::string& prefix, TensorMap& tensors) const {
  if (learned_) cnn_.save(prefix + ".features_extractor", tensors);
}

void FeaturesExtractorNet::load(const std::string& prefix, const TensorMap& tensors) {
  if (learned_) cnn_.load(prefix + ".features_extractor", tensors);
}

void polyak_update(const FeaturesExtractorNet& source, FeaturesExtractorNet& target, float tau) {
  if (source.learned()) polyak_update(source.cnn().params(), target.cnn().params(), tau);
}

std::string FeaturesExtractorNet::export_to(PolicyGraph& graph, const std::string& encoded) const {
  return learned_ ? graph.nature_cnn(encoded, cnn_) : encoded;
}

}  // namespace rlrun
