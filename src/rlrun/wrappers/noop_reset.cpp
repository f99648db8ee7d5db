#include "rlrun/wrappers/noop_reset.hpp"

#include <stdexcept>
#include <string>

namespace rlrun {

namespace {
// Keeps the wrapper's draws apart from the env's own stream for the same seed.
constexpr uint64_t kStreamSalt = 0x6e6f6f7072657365ULL;  // "nooprese"
}  // namespace

NoopReset::NoopReset(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), noop_max_(config.noop_max), rng_(kStreamSalt) {
  const Space& actions = inner_->action_space();
  if (!actions.is_discrete() || actions.start() > 0 || actions.start() + actions.n() <= 0)
    throw std::invalid_argument(
        "NoopReset needs a Discrete action space holding action 0 (the no-op); " + inner_->id() +
        " has " + inner_->action_space().describe());
  if (noop_max_ < 1) throw std::invalid_argument("NoopReset: noop_max must be >= 1");
}

void NoopReset::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  if (seed) rng_.reseed(*seed ^ kStreamSalt);
  inner_->reset(seed, obs);
  // SB3: np_random.integers(1, noop_max + 1), then that many steps of action 0, resetting (with
  // the same keyword arguments, so the same seed) when one ends the episode.
  const int noops = 1 + static_cast<int>(rng_.below(static_cast<uint64_t>(noop_max_)));
  const float noop = 0.0f;
  for (int i = 0; i < noops; ++i) {
    const StepResult r = inner_->step(std::span<const float>(&noop, 1), obs);
    if (r.terminated || r.truncated) inner_->reset(seed, obs);
  }
}

}  // namespace rlrun
