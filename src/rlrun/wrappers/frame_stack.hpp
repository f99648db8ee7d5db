#pragma once
// FrameStack: the last `n_stack` observations side by side, oldest first, newest last.
// Shape (n_stack, *obs_shape) as gymnasium/wrappers/stateful_observation.py's
// FrameStackObservation; for 1-D observations the flat vector is exactly SB3's VecFrameStack
// (stable_baselines3/common/vec_env/stacked_observations.py, stacking on the last axis).
// After reset() the older frames are zeros (`padding: zero`, SB3 VecFrameStack and rl-zoo's
// `frame_stack`) or copies of the first observation (`padding: reset`, Gymnasium's default).
// The final observation of an episode holds that episode's frames; the next reset starts a
// fresh stack.
// A Dict observation is stacked key by key, as SB3's StackedObservations does for Dict spaces:
// every key must be a Box, and each becomes the stack of its own last n_stack values (the
// Dict's flat layout: key after key in sorted order, each key's frames oldest first).
// `layout: sb3` gives SB3 VecFrameStack's shapes instead (rl-zoo's `frame_stack`): frames are
// concatenated along an existing axis — the channel axis of an image (SB3's is_image_space: 3
// dimensions, bounds 0-255; channels first when the first dimension is the smallest), the last
// axis otherwise, or the one `channels_order` names — so stacked (84, 84, 1) frames are
// (84, 84, n_stack), an image a CnnPolicy reads. Along the last axis each position holds its
// n_stack values side by side, as np.concatenate(..., axis=-1) lays them out.
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class FrameStack : public Wrapper {
 public:
  // Observations only (rlrun export reads this wrapper's observations: env/wrapper.hpp).
  bool exports_action_unchanged() const override { return true; }
  struct Config {
    int n_stack = 4;                      // frames per observation
    std::string padding = "zero";         // what fills the stack after reset: zero | reset
    std::string layout = "new_axis";      // new_axis (Gymnasium) | sb3 (VecFrameStack)
    std::string channels_order = "auto";  // sb3 layout: auto | first | last
    template <class V>
    void visit(V& v) {
      v("n_stack", n_stack, "number of consecutive observations stacked (oldest first)",
        in_range(1, 1000));
      v("padding", padding,
        "frames before the first one after reset: zero (SB3 VecFrameStack) or reset (copies, "
        "Gymnasium)");
      v("layout", layout,
        "new_axis: shape (n_stack, *shape) (Gymnasium FrameStackObservation); sb3: along the "
        "channel or last axis (SB3 VecFrameStack)",
        OneOf{{"new_axis", "sb3"}});
      v("channels_order", channels_order,
        "sb3 layout: the axis frames join, auto (an image's channel axis, else the last), first "
        "or last (SB3's channels_order)",
        OneOf{{"auto", "first", "last"}});
    }
  };
  // Throws std::invalid_argument for an observation space that is not a Box or a Dict of
  // Boxes, n_stack < 1, or an unknown padding, layout or channels_order.
  FrameStack(EnvPtr inner, const Config& config);
  explicit FrameStack(EnvPtr inner) : FrameStack(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 protected:
  void write_own_state(StateWriter& out) const override {
    out.put_vector("frame_stack/frames", stack_);
  }
  void read_own_state(const StateReader& in) override {
    in.get_into<float>("frame_stack/frames", stack_);
  }

 private:
  void push(std::span<float> obs);
  // A Box (a Dict key, or the whole observation): `dim` floats at `in` in the inner
  // observation, stacked as n_stack * dim floats at `out` in ours. The frame is `dim / block`
  // blocks of `block` floats, and the stack holds each block's n_stack copies side by side,
  // oldest first (a new leading axis or axis 0: one block; the last axis: its length).
  struct Part {
    int in = 0, out = 0, dim = 0, block = 0;
  };
  // The axis frames are stacked on: -1 for a new leading axis, else an axis of the Box.
  static int stack_axis(const Space& box, const Config& config);
  static Space stacked(const Space& box, int n_stack, int axis);
  static int block_of(const Space& box, int axis);

  Space space_;
  std::vector<Part> parts_;
  int n_stack_;
  bool pad_with_reset_;
  int frame_dim_;
  std::vector<float> frame_;  // the inner observation
  std::vector<float> stack_;  // n_stack * frame_dim: each part's frames, oldest first
};

// Gymnasium 1.0's FrameStackObservation under its own name and keywords: `stack_size` frames on
// a new leading axis, `padding_type` reset (copies of the first frame, Gymnasium's default) or
// zero.
class FrameStackObservation : public FrameStack {
 public:
  struct Config {
    int stack_size = 4;
    std::string padding_type = "reset";
    template <class V>
    void visit(V& v) {
      v("stack_size", stack_size, "number of consecutive observations stacked (oldest first)",
        in_range(1, 1000));
      v("padding_type", padding_type,
        "frames before the first one after reset: reset (copies, Gymnasium's default) or zero",
        OneOf{{"reset", "zero"}});
    }
  };
  FrameStackObservation(EnvPtr inner, const Config& config)
      : FrameStack(std::move(inner), as_frame_stack(config)) {}

 private:
  static FrameStack::Config as_frame_stack(const Config& config) {
    FrameStack::Config c;
    c.n_stack = config.stack_size;
    c.padding = config.padding_type;
    return c;
  }
};

}  // namespace rlrun
