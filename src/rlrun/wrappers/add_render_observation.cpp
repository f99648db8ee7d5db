#include "rlrun/wrappers/add_render_observation.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "rlrun/render/draw_pixels.hpp"

namespace rlrun {

namespace {
// The frame to draw into: the config's size, else the env's render size.
Frame observed_frame(const Env& inner, const AddRenderObservation::Config& config) {
  const RenderSpec spec = inner.render_spec();
  if (spec.width <= 0 || spec.height <= 0)
    throw std::invalid_argument("AddRenderObservation: " + inner.id() +
                                " cannot render, so it has no pixels to observe");
  return Frame(config.width > 0 ? config.width : spec.width,
               config.height > 0 ? config.height : spec.height);
}
}  // namespace

AddRenderObservation::AddRenderObservation(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), frame_(observed_frame(*inner_, config)) {
  const Space pixels = Space::image({frame_.height(), frame_.width(), 3});
  if (config.render_only) {
    space_ = pixels;
    state_.resize(static_cast<size_t>(inner_->observation_space().flat_dim()));
    return;
  }
  const Space& state = inner_->observation_space();
  if (state.is_dict())
    throw std::invalid_argument("AddRenderObservation: render_only: false puts " + inner_->id() +
                                "'s observation under a key, and it is a Dict already (one "
                                "level of keys, as SB3's MultiInputPolicy)");
  if (config.obs_key == config.render_key || config.obs_key.empty() || config.render_key.empty())
    throw std::invalid_argument(
        "AddRenderObservation: obs_key and render_key must be two different, non-empty keys");
  space_ = Space::dict({{config.obs_key, state}, {config.render_key, pixels}});
  const bool state_first = space_.keys()[0] == config.obs_key;
  state_at_ = space_.offset(state_first ? 0 : 1);
  pixels_at_ = space_.offset(state_first ? 1 : 0);
  state_dim_ = state.flat_dim();
}

void AddRenderObservation::observe(std::span<float> obs) {
  if (!inner_->render(frame_))
    throw std::runtime_error("AddRenderObservation: " + inner_->id() + " did not draw a frame");
  frame_.to_rgb(rgb_);
  std::copy(rgb_.begin(), rgb_.end(), obs.begin() + pixels_at_);
}

void AddRenderObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, state_dim_ ? obs.subspan(state_at_, state_dim_) : std::span<float>(state_));
  observe(obs);
}

StepResult AddRenderObservation::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(
      action, state_dim_ ? obs.subspan(state_at_, state_dim_) : std::span<float>(state_));
  observe(obs);
  return result;
}

bool AddRenderObservation::render_observation(std::span<const float> obs, Frame& frame) const {
  draw_pixels(obs.subspan(pixels_at_), frame_.height(), frame_.width(), 3, frame);
  return true;
}

}  // namespace rlrun
