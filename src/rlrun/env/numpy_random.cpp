#include "rlrun/env/numpy_random.hpp"

#include <cstddef>

namespace rlrun {

namespace {

// numpy/random/bit_generator.pyx's SeedSequence constants.
constexpr uint32_t kInitA = 0x43b0d7e5;
constexpr uint32_t kMultA = 0x931e8875;
constexpr uint32_t kInitB = 0x8b51f9dd;
constexpr uint32_t kMultB = 0x58f38ded;
constexpr uint32_t kMixMultL = 0xca01f9dd;
constexpr uint32_t kMixMultR = 0x4973f715;
constexpr int kXShift = 16;
constexpr int kPoolSize = 4;

uint32_t hashmix(uint32_t value, uint32_t& hash_const) {
  value ^= hash_const;
  hash_const *= kMultA;
  value *= hash_const;
  value ^= value >> kXShift;
  return value;
}

uint32_t mix(uint32_t x, uint32_t y) {
  uint32_t result = kMixMultL * x - kMixMultR * y;
  result ^= result >> kXShift;
  return result;
}

// pcg64.h: PCG_DEFAULT_MULTIPLIER_128.
constexpr unsigned __int128 kMultiplier =
    (static_cast<unsigned __int128>(0x2360ed051fc65da4ULL) << 64) | 0x4385df649fccf645ULL;

unsigned __int128 join(uint64_t high, uint64_t low) {
  return (static_cast<unsigned __int128>(high) << 64) | low;
}

}  // namespace

void NumpyRandom::seed_pcg(const uint32_t* entropy, int count) {
  // SeedSequence.mix_entropy: hash the entropy into the pool, mix every word into every other.
  uint32_t pool[kPoolSize];
  uint32_t hash_const = kInitA;
  for (int i = 0; i < kPoolSize; ++i) pool[i] = hashmix(i < count ? entropy[i] : 0, hash_const);
  for (int src = 0; src < kPoolSize; ++src)
    for (int dst = 0; dst < kPoolSize; ++dst)
      if (src != dst) pool[dst] = mix(pool[dst], hashmix(pool[src], hash_const));
  for (int src = kPoolSize; src < count; ++src)
    for (int dst = 0; dst < kPoolSize; ++dst)
      pool[dst] = mix(pool[dst], hashmix(entropy[src], hash_const));
  // generate_state(4, np.uint64): eight 32-bit words, read as four little-endian 64-bit ones.
  uint32_t state32[8];
  hash_const = kInitB;
  for (int i = 0; i < 8; ++i) {
    uint32_t value = pool[i % kPoolSize];
    value ^= hash_const;
    hash_const *= kMultB;
    value *= hash_const;
    value ^= value >> kXShift;
    state32[i] = value;
  }
  uint64_t val[4];
  for (int i = 0; i < 4; ++i)
    val[i] = static_cast<uint64_t>(state32[2 * i]) | static_cast<uint64_t>(state32[2 * i + 1])
                                                         << 32;
  // pcg64_set_seed -> pcg_setseq_128_srandom_r(state = val[0:2], seq = val[2:4]).
  increment_ = (join(val[2], val[3]) << 1) | 1;
  state_ = 0;
  state_ = state_ * kMultiplier + increment_;
  state_ += join(val[0], val[1]);
  state_ = state_ * kMultiplier + increment_;
}

void NumpyRandom::reseed(uint64_t seed) {
  // _int_to_uint32_array: the int's 32-bit words, least significant first; 0 is one word.
  const uint32_t words[2] = {static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)};
  seed_pcg(words, seed >> 32 ? 2 : 1);
}

void NumpyRandom::reseed_from_entropy(const std::array<uint32_t, 4>& words) {
  // randbits(128) as an int: its top zero words are not part of the entropy.
  int count = 4;
  while (count > 1 && words[static_cast<size_t>(count - 1)] == 0) --count;
  seed_pcg(words.data(), count);
}

uint64_t NumpyRandom::next_u64() {
  // pcg64_next64: step, then XSL-RR of the new state.
  state_ = state_ * kMultiplier + increment_;
  const uint64_t high = static_cast<uint64_t>(state_ >> 64);
  const uint64_t low = static_cast<uint64_t>(state_);
  const unsigned rotation = static_cast<unsigned>(state_ >> 122);
  const uint64_t x = high ^ low;
  return (x >> rotation) | (x << ((64 - rotation) & 63));
}

std::array<uint64_t, 4> NumpyRandom::words() const {
  return {static_cast<uint64_t>(state_ >> 64), static_cast<uint64_t>(state_),
          static_cast<uint64_t>(increment_ >> 64), static_cast<uint64_t>(increment_)};
}

void NumpyRandom::set_words(const std::array<uint64_t, 4>& words) {
  state_ = join(words[0], words[1]);
  increment_ = join(words[2], words[3]) | 1;  // PCG's increment is odd
}

}  // namespace rlrun
