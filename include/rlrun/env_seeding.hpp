#pragma once
// Gymnasium's seeding contract for an env's random stream (gymnasium/core.py Env.reset:
// `if seed is not None: self._np_random, self._np_random_seed = seeding.np_random(seed)`):
// a seed reseeds the stream, no seed continues it, and the very first reset of an env that was
// never seeded draws the seed from OS entropy (Env.np_random seeds itself with
// `seeding.np_random()`, i.e. entropy, on first use). EnvSeeding holds the stream and the
// never-seeded flag that contract needs, and saves both for checkpoints, so every built-in env
// gets the same rules and the same state keys.
#include <cstdint>
#include <optional>
#include <random>

#include "rlrun/rng.hpp"
#include "rlrun/state.hpp"

namespace rlrun {

class EnvSeeding {
 public:
  // Call at the start of the env's reset(), where Gymnasium envs call super().reset(seed=seed).
  void on_reset(std::optional<uint64_t> seed) {
    if (seed) {
      rng_.reseed(*seed);
      ever_seeded_ = true;
    } else if (!ever_seeded_) {
      std::random_device device;
      rng_.reseed((static_cast<uint64_t>(device()) << 32) ^ device());
      ever_seeded_ = true;
    }
  }

  Rng& rng() { return rng_; }
  const Rng& rng() const { return rng_; }

  // Keys "rng" and "ever_seeded", under the env's own state prefix: the names the envs wrote
  // before this class existed, so their checkpoints still load.
  void write_state(StateWriter& out) const {
    out.put_rng("rng", rng_);
    out.put_bool("ever_seeded", ever_seeded_);
  }
  void read_state(const StateReader& in) {
    in.get_rng("rng", rng_);
    ever_seeded_ = in.get_bool("ever_seeded");
  }

 private:
  Rng rng_;
  bool ever_seeded_ = false;
};

}  // namespace rlrun
