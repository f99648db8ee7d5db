#pragma once
// EnvSeeding's contract (include/rlrun/env_seeding.hpp: a seed reseeds, no seed continues, the
// first reset of a never-seeded env draws OS entropy) over numpy's stream (NumpyRandom), for
// the envs whose reset draws must equal Gymnasium's for the same seed: the classic-control
// tasks, whose initial state is all a seed decides. Saved for checkpoints as "np_random" (PCG64's
// state and increment) and "ever_seeded".
#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "rlrun/env/numpy_random.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/state.hpp"

namespace rlrun {

class GymnasiumSeeding {
 public:
  // Call at the start of the env's reset(), where Gymnasium envs call super().reset(seed=seed).
  void on_reset(std::optional<uint64_t> seed) {
    if (seed) {
      random_.reseed(*seed);
      ever_seeded_ = true;
    } else if (!ever_seeded_) {
      // seeding.np_random(None): SeedSequence() with 128 bits of OS entropy.
      std::random_device device;
      random_.reseed_from_entropy({device(), device(), device(), device()});
      ever_seeded_ = true;
    }
  }

  NumpyRandom& random() { return random_; }

  void write_state(StateWriter& out) const {
    const std::array<uint64_t, 4> words = random_.words();
    out.put_span<uint64_t>("np_random", words);
    out.put_bool("ever_seeded", ever_seeded_);
  }
  // Checkpoints of rlrun before this class held "rng" (rlrun's own generator) instead: such
  // an env continues from a stream seeded by that generator's next draw, deterministically.
  void read_state(const StateReader& in) {
    if (in.has("np_random")) {
      const std::vector<uint64_t> w = in.get_span<uint64_t>("np_random", 4);
      random_.set_words({w[0], w[1], w[2], w[3]});
    } else {
      Rng old;
      in.get_rng("rng", old);
      random_.reseed(old.next_u64());
    }
    ever_seeded_ = in.get_bool("ever_seeded");
  }

 private:
  NumpyRandom random_;
  bool ever_seeded_ = false;
};

}  // namespace rlrun
