#include "rlrun/wrappers/frame_stack.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

Space FrameStack::stacked(const Space& box, int n_stack) {
  std::vector<float> low, high;
  for (int k = 0; k < n_stack; ++k) {
    low.insert(low.end(), box.low().begin(), box.low().end());
    high.insert(high.end(), box.high().begin(), box.high().end());
  }
  std::vector<int> shape{n_stack};
  shape.insert(shape.end(), box.shape().begin(), box.shape().end());
  return Space::box(std::move(low), std::move(high), std::move(shape));
}

FrameStack::FrameStack(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), n_stack_(config.n_stack) {
  const Space& inner_space = inner_->observation_space();
  if (!inner_space.is_box() && !inner_space.is_dict())
    throw std::invalid_argument("FrameStack needs a Box or Dict observation space, " +
                                inner_->id() + " has " + inner_space.describe());
  // SB3 StackedObservations: a Dict's keys are stacked one by one, and each must be a Box.
  for (size_t i = 0; i < inner_space.keys().size(); ++i)
    if (!inner_space.subspaces()[i].is_box())
      throw std::invalid_argument("FrameStack stacks Box keys only (SB3 VecFrameStack), " +
                                  inner_->id() + "'s key '" + inner_space.keys()[i] + "' is " +
                                  inner_space.subspaces()[i].describe());
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
  if (inner_space.is_box()) {
    parts_.push_back({0, 0, frame_dim_});
    space_ = stacked(inner_space, n_stack_);
  } else {
    std::vector<std::pair<std::string, Space>> keys;
    for (size_t i = 0; i < inner_space.keys().size(); ++i) {
      const Space& key_space = inner_space.subspaces()[i];
      const int offset = inner_space.offset(i);
      parts_.push_back({offset, offset * n_stack_, key_space.flat_dim()});
      keys.emplace_back(inner_space.keys()[i], stacked(key_space, n_stack_));
    }
    space_ = Space::dict(std::move(keys));
  }
  frame_.resize(frame_dim_);
  stack_.assign(static_cast<size_t>(n_stack_) * frame_dim_, 0.0f);
}

void FrameStack::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, frame_);
  for (const Part& p : parts_) {
    const float* frame = frame_.data() + p.in;
    for (int k = 0; k < n_stack_; ++k) {
      float* slot = stack_.data() + p.out + static_cast<size_t>(k) * p.dim;
      if (pad_with_reset_ || k == n_stack_ - 1)
        std::copy(frame, frame + p.dim, slot);
      else
        std::fill(slot, slot + p.dim, 0.0f);
    }
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
  for (const Part& p : parts_) {
    float* begin = stack_.data() + p.out;
    float* end = begin + static_cast<size_t>(n_stack_) * p.dim;
    std::copy(begin + p.dim, end, begin);
    std::copy(frame_.data() + p.in, frame_.data() + p.in + p.dim, end - p.dim);
  }
  std::copy(stack_.begin(), stack_.end(), obs.begin());
}

}  // namespace rlrun
