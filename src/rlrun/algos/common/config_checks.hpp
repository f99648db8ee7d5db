#pragma once
// Checks every algorithm's static check() shares (registry: AlgorithmEntry::check): they run
// when the experiment is parsed, with the env's spaces, so a setting that cannot work is
// reported with its key before anything trains, not as an exception from a constructor.
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/core/config_checks.hpp"

namespace rlrun {

inline constexpr int kMaxLayerWidth = 65536;
inline constexpr int kMaxLayers = 64;

// Per-layer bounds of a `net_arch` list (the field constraint) and its length.
inline Bounds layer_width() { return in_range(1, kMaxLayerWidth); }
void check_net_arch(ConfigProblems& out, const std::string& key, const std::vector<int>& net_arch);
// The same for a net_arch with an actor and a critic list (net_arch.hpp): each list once.
void check_net_arch(ConfigProblems& out, const std::string& key, const std::vector<int>& actor,
                    const std::vector<int>& critic);

// Parameters of an MLP in -> hidden... -> out (weights and biases).
double mlp_parameter_count(int in, const std::vector<int>& hidden, int out);

// Memory of `networks` MLPs of this shape, trained with Adam (weights, gradients, two moments,
// a target copy) and their activations for `batch` samples; a problem at `key` when it cannot
// fit this machine.
void check_network_memory(ConfigProblems& out, const std::string& key, int in,
                          const std::vector<int>& hidden, int outputs, int networks, double batch);

// A replay buffer of `buffer_size` transitions: obs and (unless `optimize_memory_usage`) next
// obs in their spaces' dtypes (observation_columns.hpp), action, reward and done in float32.
void check_replay_memory(ConfigProblems& out, int64_t buffer_size, bool optimize_memory_usage,
                         const AlgorithmSetup& setup);

// SB3's gradient_steps: >= 1, or -1 (as many as env steps collected).
void check_gradient_steps(ConfigProblems& out, int gradient_steps);

// A Box action space with finite bounds low < high (actors that end in tanh). Observations may
// be any space: the networks see them through an ObservationEncoder.
void check_box_actor_spaces(ConfigProblems& out, const AlgorithmSetup& setup);

// SB3 BaseAlgorithm: "generalized State-Dependent Exploration (gSDE) can only be used with
// continuous actions": a problem at `use_sde` unless the actions are a Box.
void check_use_sde(ConfigProblems& out, bool use_sde, const AlgorithmSetup& setup);

// What a network sees of one observation (ObservationEncoder::features_dim: one-hots for
// Discrete values, Dict keys concatenated); when the space has too many features, the problem
// is added under `id` and the flat size returned so that later checks can still run.
int network_input_dim(ConfigProblems& out, const Space& observation_space);

// What the heads read after SB3's features extractor: network_input_dim for FlattenExtractor;
// for NatureCNN, features_dim, with the image checked (SB3's message under `key`); for
// CombinedExtractor (a Dict, or a problem under `key`), cnn_output_dim per image key and the
// other keys' widths. The memory of `networks` such extractors is checked: each CNN's weights
// with their gradients and Adam moments, the activations of `batch` images forward and
// backward, and a worker's im2col patches per CPU.
int features_extractor_output_dim(ConfigProblems& out, const std::string& key,
                                  const FeaturesExtractorSettings& extractor,
                                  const Space& observation_space, int networks, double batch);

}  // namespace rlrun
