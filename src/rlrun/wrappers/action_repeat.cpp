#include "rlrun/wrappers/action_repeat.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rlrun {

ActionRepeat::ActionRepeat(EnvPtr inner, int skip, bool max_pool, const char* name)
    : Wrapper(std::move(inner)), skip_(skip), max_pool_(max_pool) {
  if (skip_ < 1) throw std::invalid_argument(std::string(name) + ": skip must be >= 1");
  const Space& s = inner_->observation_space();
  if (max_pool_) {
    if (!s.is_box())
      throw std::invalid_argument(std::string(name) +
                                  " max-pools Box observations (SB3 MaxAndSkipEnv); " +
                                  inner_->id() + " has " + s.describe());
    // SB3: np.zeros((2,) + shape), made once with the wrapper.
    last_two_.assign(2 * static_cast<size_t>(s.flat_dim()), 0.0f);
    scratch_.resize(static_cast<size_t>(s.flat_dim()));
  }
}

StepResult ActionRepeat::step(std::span<const float> action, std::span<float> obs) {
  StepResult total;
  const size_t dim = scratch_.size();
  for (int i = 0; i < skip_; ++i) {
    std::span<float> into = obs;
    if (max_pool_)
      into = i == skip_ - 2   ? std::span<float>(last_two_.data(), dim)
             : i == skip_ - 1 ? std::span<float>(last_two_.data() + dim, dim)
                              : std::span<float>(scratch_);
    const StepResult r = inner_->step(action, into);
    total.reward += r.reward;  // SB3 / rl-zoo: total_reward += float(reward)
    total.terminated = r.terminated;
    total.truncated = r.truncated;
    if (r.terminated || r.truncated) break;
  }
  if (max_pool_)
    for (size_t k = 0; k < dim; ++k) obs[k] = std::max(last_two_[k], last_two_[dim + k]);
  return total;
}

void ActionRepeat::write_own_state(StateWriter& out) const {
  if (max_pool_) out.put_vector("action_repeat/last_two", last_two_);
}

void ActionRepeat::read_own_state(const StateReader& in) {
  if (max_pool_) in.get_into<float>("action_repeat/last_two", last_two_);
}

}  // namespace rlrun
