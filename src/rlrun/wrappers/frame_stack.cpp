#include "rlrun/wrappers/frame_stack.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

FrameStack::FrameStack(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), n_stack_(config.n_stack) {
  const Space& inner_space = inner_->observation_space();
  if (!inner_space.is_box())
    throw std::invalid_argument("FrameStack needs a Box observation space, " + inner_->id() +
                                " has " + inner_space.describe());
  if (n_stack_ < 1) throw std::invalid_argument("FrameStack: n_stack must be >= 1");
  if (config.padding != "zero" && config.padding != "reset")
    throw std::invalid_argument("FrameStack: padding must be 'zero' or 'reset', not '" +
                                config.padding + "'");
  pad_with_reset_ = config.padding == "reset";
  frame_dim_ = inner_space.flat_dim();
  // A stacked observation of more than 2^24 floats (64 MiB per env step) is a typo, not a
  // network input.
  if (static_cast<int64_t>(n_stack_) * frame_dim_ > (int64_t{1} << 24))
    throw std::invalid_argument("FrameStack: n_stack " + std::to_string(n_stack_) + " x " +
                                std::to_string(frame_dim_) +
                                " floats per observation is more than 2^24");
  std::vector<float> low, high;
  for (int k = 0; k < n_stack_; ++k) {
    low.insert(low.end(), inner_space.low().begin(), inner_space.low().end());
    high.insert(high.end(), inner_space.high().begin(), inner_space.high().end());
  }
  std::vector<int> shape{n_stack_};
  shape.insert(shape.end(), inner_space.shape().begin(), inner_space.shape().end());
  space_ = Space::box(std::move(low), std::move(high), std::move(shape));
  frame_.resize(frame_dim_);
  stack_.assign(static_cast<size_t>(n_stack_) * frame_dim_, 0.0f);
}

void FrameStack::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, frame_);
  for (int k = 0; k < n_stack_; ++k) {
    float* slot = stack_.data() + static_cast<size_t>(k) * frame_dim_;
    if (pad_with_reset_ || k == n_stack_ - 1)
      std::copy(frame_.begin(), frame_.end(), slot);
    else
      std::fill(slot, slot + frame_dim_, 0.0f);
  }
  std::copy(stack_.begin(), stack_.end(), obs.begin());
}

StepResult FrameStack::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, frame_);
  push(obs);
  return result;
}

void FrameStack::push(std::span<float> obs) {
  // Drop the oldest frame, append the newest (SB3: np.roll by -frame_dim, then write the tail).
  std::copy(stack_.begin() + frame_dim_, stack_.end(), stack_.begin());
  std::copy(frame_.begin(), frame_.end(), stack_.end() - frame_dim_);
  std::copy(stack_.begin(), stack_.end(), obs.begin());
}

}  // namespace rlrun
