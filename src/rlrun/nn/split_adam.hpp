#pragma once
// torch.optim.Adam over one network's parameter vector with its element-wise work in two parts
// (batch_split.hpp param_part): two Adams over the vector's two parts, stepped at once. Adam is
// element-wise with one step count, so this is exactly one Adam over the whole vector. Also
// the total gradient norm of torch.nn.utils.clip_grad_norm_, summed the same way, and the
// clipping applied inside the step. DQN uses it (its update is short, so the optimizer's pass
// over the parameters is a large share of it).
#include <array>

#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/param_block.hpp"

namespace rlrun {

class SplitAdam {
 public:
  SplitAdam() = default;
  // `block` must outlive the optimizer and stay where it is (see ParamBlock). `pool` runs the
  // two parts (null: both on the calling thread).
  explicit SplitAdam(ParamBlock block, AdamConfig config = {}, ThreadPool* pool = nullptr);

  // The L2 norm of the whole gradient: each part's sum of squares (in double, over float chunks),
  // part 0's plus part 1's.
  float grad_norm() const;
  // The sum of squares grad_norm() takes the root of, in double: several optimizers' gradients
  // clipped together (DQN's CNN and head) add theirs.
  double grad_sum_of_squares() const;
  // Multiplies the gradient by grad_scale unless it is 1 (clip_grad_norm_'s coefficient), then
  // one Adam step with learning rate lr.
  void step(float lr, float grad_scale = 1.0f);

  // The two parts' optimizers (checkpoints: their moments and step counts).
  Adam& part(int k) { return parts_[k]; }
  const Adam& part(int k) const { return parts_[k]; }

 private:
  ParamBlock block_;
  std::array<Adam, 2> parts_;
  ThreadPool* pool_ = nullptr;
};

}  // namespace rlrun
