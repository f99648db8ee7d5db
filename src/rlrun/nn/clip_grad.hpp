#pragma once
// torch.nn.utils.clip_grad_norm_ with the L2 norm, as SB3's PPO/A2C call it with max_grad_norm.
#include <span>

#include "rlrun/nn/param_block.hpp"

namespace rlrun {

// Total L2 norm of all gradients taken together; if max_norm / (total + 1e-6) < 1 every gradient
// is multiplied by that factor. Returns the norm BEFORE clipping (what torch returns and SB3
// could log). A non-finite norm is returned as is and scales the gradients to NaN, as torch's
// default error_if_nonfinite=False does. The sum of squares is accumulated in double.
float clip_grad_norm(std::span<const ParamBlock> blocks, float max_norm);

// The total L2 norm alone, no clipping.
float grad_norm(std::span<const ParamBlock> blocks);

}  // namespace rlrun
