#pragma once
// Gymnasium's seeding contract for an env's random stream (gymnasium/core.py Env.reset:
// `if seed is not None: self._np_random, self._np_random_seed = seeding.np_random(seed)`):
// a seed reseeds the stream, no seed continues it, and the very first reset of an env that was
// never seeded draws the seed from OS entropy. Shared by every built-in env, with the two
// values that hold the contract's state in checkpoints.
#include <cstdint>
#include <optional>
#include <random>

#include "rlrun/core/rng.hpp"
#include "rlrun/core/state_dict.hpp"

namespace rlrun {

inline void seed_on_reset(Rng& rng, bool& ever_seeded, std::optional<uint64_t> seed) {
  if (seed) {
    rng.reseed(*seed);
    ever_seeded = true;
  } else if (!ever_seeded) {
    std::random_device device;
    rng.reseed((static_cast<uint64_t>(device()) << 32) ^ device());
    ever_seeded = true;
  }
}

inline void write_seeding_state(StateWriter& out, const Rng& rng, bool ever_seeded) {
  out.put_rng("rng", rng);
  out.put_bool("ever_seeded", ever_seeded);
}

inline void read_seeding_state(const StateReader& in, Rng& rng, bool& ever_seeded) {
  in.get_rng("rng", rng);
  ever_seeded = in.get_bool("ever_seeded");
}

}  // namespace rlrun
