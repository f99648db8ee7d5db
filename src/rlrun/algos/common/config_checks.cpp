#include "rlrun/algos/common/config_checks.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/observation_columns.hpp"
#include "rlrun/env/image_space.hpp"
#include "rlrun/env/observation_encoder.hpp"

#include <cmath>

#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/resource_limits.hpp"
#include "rlrun/nn/batch_split.hpp"

namespace rlrun {

void check_net_arch(ConfigProblems& out, const std::string& key, const std::vector<int>& net_arch) {
  if (static_cast<int>(net_arch.size()) > kMaxLayers)
    out.push_back({key, "has " + std::to_string(net_arch.size()) + " layers; at most " +
                            std::to_string(kMaxLayers)});
}

void check_net_arch(ConfigProblems& out, const std::string& key, const std::vector<int>& actor,
                    const std::vector<int>& critic) {
  check_net_arch(out, key, actor);
  if (critic != actor) check_net_arch(out, key, critic);
}

double mlp_parameter_count(int in, const std::vector<int>& hidden, int out) {
  double count = 0;
  double previous = in;
  for (int width : hidden) {
    count += (previous + 1) * width;
    previous = width;
  }
  return count + (previous + 1) * out;
}

void check_network_memory(ConfigProblems& out, const std::string& key, int in,
                          const std::vector<int>& hidden, int outputs, int networks, double batch) {
  // Weights, gradients, Adam's two moments and a target or replica copy: 5 floats each; a
  // minibatch cut into more than two parts (nn/batch_split.hpp) keeps one more gradient per
  // further replica.
  const double per_network = mlp_parameter_count(in, hidden, outputs);
  const int parts = column_parts(static_cast<Eigen::Index>(std::clamp(batch, 1.0, 1e9)),
                                 static_cast<Eigen::Index>(std::min(per_network, 1e15)));
  const double floats_per_parameter = 5.0 + std::max(0, parts - 2);
  const double parameters = per_network * networks;
  double widest = 0;
  for (int width : hidden) widest += width;
  const double activations = widest * std::max(batch, 1.0) * networks * 4;  // forward + backward
  const std::string problem = memory_problem(
      (parameters * floats_per_parameter + activations) * sizeof(float), "this network");
  if (!problem.empty()) out.push_back({key, problem});
}

void check_replay_memory(ConfigProblems& out, int64_t buffer_size, bool optimize_memory_usage,
                         const AlgorithmSetup& setup) {
  const double observations = (optimize_memory_usage ? 1.0 : 2.0) *
                              ObservationColumns::bytes_per_observation(setup.observation_space);
  const double row = observations + (setup.action_space.flat_dim() + 2.0) * sizeof(float);
  const std::string problem =
      memory_problem(static_cast<double>(buffer_size) * row,
                     "a replay buffer of " + std::to_string(buffer_size) + " transitions");
  if (!problem.empty()) out.push_back({"buffer_size", problem});
}

void check_gradient_steps(ConfigProblems& out, int gradient_steps) {
  if (gradient_steps == 0 || gradient_steps < -1)
    out.push_back({"gradient_steps", "must be >= 1, or -1 (as many as env steps collected), got " +
                                         std::to_string(gradient_steps)});
}

void check_box_actor_spaces(ConfigProblems& out, const AlgorithmSetup& setup) {
  const Space& a = setup.action_space;
  if (!a.is_box()) return;  // make_env has named the wrapper that fixes it
  for (size_t i = 0; i < a.low().size(); ++i)
    if (!std::isfinite(a.low()[i]) || !std::isfinite(a.high()[i]) || !(a.low()[i] < a.high()[i])) {
      out.push_back({"id", "the action space " + a.describe() +
                               " must have finite bounds low < high (the actor ends in tanh; "
                               "add a ClipAction or RescaleAction wrapper)"});
      return;
    }
}

void check_use_sde(ConfigProblems& out, bool use_sde, const AlgorithmSetup& setup) {
  if (use_sde && !setup.action_space.is_box())
    out.push_back({"use_sde", "gSDE can only be used with continuous (Box) actions, not " +
                                  setup.action_space.describe()});
}

int network_input_dim(ConfigProblems& out, const Space& observation_space) {
  try {
    return ObservationEncoder(observation_space).features_dim();
  } catch (const std::invalid_argument& e) {
    out.push_back({"id", e.what()});
    return observation_space.flat_dim();
  }
}

namespace {

// Floats of one NatureCNN on `image` with `features` outputs: the linear layer dominates the
// weights (the last convolution's output times features, as parameters, gradients and Adam's
// two moments); a batch keeps every layer's output and its gradient (nn/nature_cnn.cpp); each
// worker im2cols one image at a time (the first layer's patches are the largest: ~4x the image).
double nature_cnn_floats(const ImageInput& image, int features, double batch) {
  const auto shapes = NatureCnn::conv_shapes(image);
  const auto flatten = static_cast<double>(shapes.back().out_size());
  double per_image = image.size() + features, patches = 0;
  for (const Conv2dShape& s : shapes) {
    per_image += static_cast<double>(s.out_size());
    patches = std::max(patches, static_cast<double>(s.patch_size() * s.out_pixels()));
  }
  return flatten * features * 4 + per_image * 2 * std::max(batch, 1.0) +
         patches * 2 * available_cpus();
}

}  // namespace

int features_extractor_output_dim(ConfigProblems& out, const std::string& key,
                                  const FeaturesExtractorSettings& e, const Space& space,
                                  int networks, double batch) {
  if (e.kind == FeaturesExtractor::kFlatten) return network_input_dim(out, space);
  try {
    double floats = 0;
    int features = 0;
    if (e.kind == FeaturesExtractor::kNatureCnn) {
      floats =
          nature_cnn_floats(require_image_input(space, e.normalize_images), e.features_dim, batch);
      features = e.features_dim;
    } else {
      // SB3 CombinedExtractor: a NatureCNN per image key, the rest flattened.
      for (const CombinedKey& k : combined_extractor_keys(space)) {
        if (k.image) floats += nature_cnn_floats(*k.image, e.cnn_output_dim, batch);
        features += k.image ? e.cnn_output_dim : k.encoded_width;
      }
    }
    const std::string problem =
        memory_problem(networks * floats * sizeof(float),
                       "NatureCNN's weights and the activations of a batch of " +
                           std::to_string(static_cast<int64_t>(std::max(batch, 1.0))) + " images");
    if (!problem.empty()) out.push_back({key, problem});
    return features;
  } catch (const std::invalid_argument& ex) {
    out.push_back({key, ex.what()});
  }
  // A width for the checks that follow.
  return e.kind == FeaturesExtractor::kNatureCnn ? e.features_dim : network_input_dim(out, space);
}

}  // namespace rlrun
