#pragma once
// Divergence detection: a NaN or inf in a logged loss or in a parameter stops training with an
// error naming the step and the quantity, before it reaches a checkpoint or the model file (SB3
// has no such check; its users discover NaN weights at evaluation time).
#include <string>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/tensor.hpp"

namespace rlrun {

// "train/value_loss is nan" for the first non-finite loss (train/*loss*) recorded since the
// last dump, or "".
std::string describe_non_finite(const LogRow& row);

// "parameter actor.mu.weight has 12 non-finite values (first: inf)" for the first tensor with
// a NaN or inf among float tensors, or "". `noun` names what the tensors are.
std::string describe_non_finite(const TensorMap& tensors, const std::string& noun = "parameter");

}  // namespace rlrun
