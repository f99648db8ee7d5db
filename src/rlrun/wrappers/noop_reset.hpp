#pragma once
// NoopReset (stable_baselines3/common/atari_wrappers.py NoopResetEnv): after each reset, a
// random number of "do nothing" steps, uniform in [1, noop_max], so episodes start from
// varied states; an episode that ends during them is reset again. As in SB3, action 0 of a
// Discrete action space is the no-op (SB3 checks Atari's action meanings; rlrun's envs have
// none, so choosing this wrapper says action 0 does nothing).
// The count is drawn from the wrapper's own generator, reseeded by every seeded reset (SB3 draws
// from the env's np_random, which rlrun's envs do not share), and saved with checkpoints.
#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class NoopReset : public Wrapper {
 public:
  // The no-ops happen inside reset(): observations and actions pass as they are.
  bool exports_unchanged() const override { return true; }
  struct Config {
    int noop_max = 30;
    template <class V>
    void visit(V& v) {
      v("noop_max", noop_max, "most no-op steps (action 0) after a reset; at least one is taken",
        in_range(1, 100000));
    }
  };
  // Throws std::invalid_argument unless the action space is Discrete, or for noop_max < 1.
  NoopReset(EnvPtr inner, const Config& config);
  explicit NoopReset(EnvPtr inner) : NoopReset(std::move(inner), Config()) {}

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;

 protected:
  void write_own_state(StateWriter& out) const override { out.put_rng("noop_reset/rng", rng_); }
  void read_own_state(const StateReader& in) override { in.get_rng("noop_reset/rng", rng_); }

 private:
  int noop_max_;
  Rng rng_;
};

}  // namespace rlrun
