#pragma once
// numpy's random stream as Gymnasium seeds an env's np_random (gymnasium/utils/seeding.py
// np_random: `np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))`), so that
// `reset(seed=s)` of rlrun's classic-control envs draws the initial state Gymnasium's draws,
// bit for bit, and an SB3 model plays the same episodes in both (docs/sb3_models.md).
//  * SeedSequence (numpy/random/bit_generator.pyx): the seed's 32-bit words hashed into a pool
//    of four, which generate_state(4, uint64) expands into PCG64's state and increment;
//  * PCG64 (numpy/random/src/pcg64/pcg64.h): a 128-bit LCG whose output is XSL-RR;
//  * Generator.random / uniform (numpy/random/src/distributions/distributions.c):
//    (next_uint64 >> 11) * 2^-53, and low + (high - low) * that.
#include <array>
#include <cstdint>

namespace rlrun {

class NumpyRandom {
 public:
  explicit NumpyRandom(uint64_t seed = 0) { reseed(seed); }

  // As PCG64(SeedSequence(seed)) for a non-negative Python int `seed`.
  void reseed(uint64_t seed);
  // As PCG64(SeedSequence(entropy)) with 128 bits of entropy (numpy draws them from the OS
  // when no seed is given): `words` least significant first.
  void reseed_from_entropy(const std::array<uint32_t, 4>& words);

  uint64_t next_u64();
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }

  // state high, state low, increment high, increment low: what a checkpoint saves.
  std::array<uint64_t, 4> words() const;
  void set_words(const std::array<uint64_t, 4>& words);

 private:
  void seed_pcg(const uint32_t* entropy, int count);
  unsigned __int128 state_ = 0;
  unsigned __int128 increment_ = 1;
};

}  // namespace rlrun
