#include "rlrun/wrappers/frame_stack.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/env/image_space.hpp"

namespace rlrun {

int FrameStack::stack_axis(const Space& box, const Config& config) {
  if (config.layout == "new_axis") return -1;
  const int last = static_cast<int>(box.shape().size()) - 1;
  if (config.channels_order == "first") return 0;
  if (config.channels_order == "last") return last;
  // SB3 StackedObservations.compute_stacking: an image stacks on its channel axis
  // (is_image_space_channels_first: the smallest dimension first), anything else on the last.
  const std::optional<ImageInput> image = image_input(box, true);
  return image && !image->channels_last ? 0 : last;
}

int FrameStack::block_of(const Space& box, int axis) {
  if (axis < 0) return box.flat_dim();  // a new leading axis: the whole frame
  int block = 1;
  for (size_t d = static_cast<size_t>(axis); d < box.shape().size(); ++d) block *= box.shape()[d];
  return block;
}

Space FrameStack::stacked(const Space& box, int n_stack, int axis) {
  const int dim = box.flat_dim(), block = block_of(box, axis);
  std::vector<float> low, high;
  for (int start = 0; start < dim; start += block)
    for (int k = 0; k < n_stack; ++k) {
      low.insert(low.end(), box.low().begin() + start, box.low().begin() + start + block);
      high.insert(high.end(), box.high().begin() + start, box.high().begin() + start + block);
    }
  std::vector<int> shape = box.shape();
  if (axis < 0)
    shape.insert(shape.begin(), n_stack);
  else
    shape[static_cast<size_t>(axis)] *= n_stack;
  return Space::box(std::move(low), std::move(high), std::move(shape), box.dtype());
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
  if (config.layout != "new_axis" && config.layout != "sb3")
    throw std::invalid_argument("FrameStack: layout must be 'new_axis' or 'sb3', not '" +
                                config.layout + "'");
  if (config.channels_order != "auto" && config.channels_order != "first" &&
      config.channels_order != "last")
    throw std::invalid_argument("FrameStack: channels_order must be auto, first or last, not '" +
                                config.channels_order + "'");
  frame_dim_ = inner_space.flat_dim();
  // A stacked observation of more than 2^24 floats (64 MiB per env step) is a typo, not a
  // network input.
  if (static_cast<int64_t>(n_stack_) * frame_dim_ > (int64_t{1} << 24))
    throw std::invalid_argument("FrameStack: n_stack " + std::to_string(n_stack_) + " x " +
                                std::to_string(frame_dim_) +
                                " floats per observation is more than 2^24");
  if (inner_space.is_box()) {
    const int axis = stack_axis(inner_space, config);
    parts_.push_back({0, 0, frame_dim_, block_of(inner_space, axis)});
    space_ = stacked(inner_space, n_stack_, axis);
  } else {
    std::vector<std::pair<std::string, Space>> keys;
    for (size_t i = 0; i < inner_space.keys().size(); ++i) {
      const Space& key_space = inner_space.subspaces()[i];
      const int offset = inner_space.offset(i);
      const int axis = stack_axis(key_space, config);
      parts_.push_back(
          {offset, offset * n_stack_, key_space.flat_dim(), block_of(key_space, axis)});
      keys.emplace_back(inner_space.keys()[i], stacked(key_space, n_stack_, axis));
    }
    space_ = Space::dict(std::move(keys));
  }
  frame_.resize(frame_dim_);
  stack_.assign(static_cast<size_t>(n_stack_) * frame_dim_, 0.0f);
}

void FrameStack::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, frame_);
  for (const Part& p : parts_)
    for (int start = 0; start < p.dim; start += p.block) {
      const float* block = frame_.data() + p.in + start;
      float* stack = stack_.data() + p.out + static_cast<size_t>(start) * n_stack_;
      for (int k = 0; k < n_stack_; ++k) {
        float* slot = stack + static_cast<size_t>(k) * p.block;
        if (pad_with_reset_ || k == n_stack_ - 1)
          std::copy(block, block + p.block, slot);
        else
          std::fill(slot, slot + p.block, 0.0f);
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
  // Drop the oldest frame, append the newest (SB3: np.roll by -frame size along the stacking
  // axis, then write the newest frame at its end), block by block.
  for (const Part& p : parts_)
    for (int start = 0; start < p.dim; start += p.block) {
      float* begin = stack_.data() + p.out + static_cast<size_t>(start) * n_stack_;
      float* end = begin + static_cast<size_t>(n_stack_) * p.block;
      std::copy(begin + p.block, end, begin);
      const float* block = frame_.data() + p.in + start;
      std::copy(block, block + p.block, end - p.block);
    }
  std::copy(stack_.begin(), stack_.end(), obs.begin());
}

}  // namespace rlrun
