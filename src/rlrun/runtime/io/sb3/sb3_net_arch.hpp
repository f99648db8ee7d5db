#pragma once
// The sizes of SB3's MLPs read off a state_dict's tensors, for reading SB3 files
// (sb3_model_file.cpp) and writing them (sb3_model_writer.cpp): SB3 builds each MLP as a torch
// Sequential of Linear layers at even indices with activations between
// (stable_baselines3/common/torch_layers.py create_mlp, MlpExtractor), so `<prefix>0.weight`,
// `<prefix>2.weight`, ... are the layers and each weight's first dimension its width.
#include <string>
#include <vector>

#include "rlrun/tensor.hpp"

namespace rlrun {

// Output sizes of the Linear layers `<prefix>0`, `<prefix>2`, ..., in order, as long as each
// layer reads the one before (its weight is [width, previous width]). The file is untrusted:
// a chain of [W, 1] weights would otherwise name W x W layers its bytes do not hold; cut at
// the first mismatch, the network built from the widths cannot load the file's tensors.
inline std::vector<int> sb3_layer_widths(const TensorMap& tensors, const std::string& prefix) {
  std::vector<int> widths;
  for (int index = 0;; index += 2) {
    const auto found = tensors.find(prefix + std::to_string(index) + ".weight");
    if (found == tensors.end() || found->second.shape.size() != 2) return widths;
    if (!widths.empty() && found->second.shape[1] != widths.back()) return widths;
    widths.push_back(static_cast<int>(found->second.shape[0]));
  }
}

// The same without the last layer (the output of a Q-network or actor: net_arch counts only
// the hidden layers).
inline std::vector<int> sb3_hidden_widths(const TensorMap& tensors, const std::string& prefix) {
  std::vector<int> widths = sb3_layer_widths(tensors, prefix);
  if (!widths.empty()) widths.pop_back();
  return widths;
}

// A MultiInputPolicy's CombinedExtractor with a NatureCNN for an image key: its convolutions
// are <network>.features_extractor.extractors.<key>.cnn.* (torch_layers.py CombinedExtractor).
inline bool sb3_has_combined_cnn(const TensorMap& tensors) {
  for (const auto& [name, tensor] : tensors)
    if (name.find("features_extractor.extractors.") != std::string::npos &&
        name.ends_with(".cnn.0.weight"))
      return true;
  return false;
}

// SAC's and TD3's critics: critic.qf0, critic.qf1, ...
inline int sb3_critic_count(const TensorMap& tensors) {
  int n = 0;
  while (tensors.count("critic.qf" + std::to_string(n) + ".0.weight")) ++n;
  return n;
}

}  // namespace rlrun
