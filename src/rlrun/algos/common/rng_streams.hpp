#pragma once
// The random streams an algorithm derives from its one seed (one explicit RNG per
// component). The weights use `seed` itself; every other purpose gets `seed ^ k<Purpose>`, so
// that, e.g., drawing more exploration noise never shifts the replay sampling. The constants
// are arbitrary odd 64-bit words (PCG's and SplitMix64's multipliers, golden-ratio bits); they
// are fixed forever, since changing one changes every run of a seed.
#include <cstdint>

namespace rlrun {

// Action sampling while collecting (on-policy samples; off-policy warmup and stochastic acting).
inline constexpr uint64_t kActionStream = 0x5851f42d4c957f2dULL;
// Off-policy exploration noise (NormalActionNoise / Ornstein-Uhlenbeck).
inline constexpr uint64_t kNoiseStream = 0x2545f4914f6cdd1dULL;
// Replay-buffer sampling (off-policy) and minibatch shuffling (on-policy).
inline constexpr uint64_t kSampleStream = 0x14057b7ef767814fULL;
// SAC's and TQC's reparameterisation noise in gradient steps, and their predict() samples.
inline constexpr uint64_t kTrainStream = 0x9e3779b97f4a7c15ULL;
inline constexpr uint64_t kPredictStream = 0xda942042e4dd58b5ULL;
// The initial weights of a features extractor an off-policy algorithm adds to its networks
// (DQN's NatureCNN), so that choosing one leaves the heads' initial weights unchanged.
inline constexpr uint64_t kFeaturesExtractorInitStream = 0x2b992ddfa23249d7ULL;
// RecurrentPPO's recurrent layers (its extractor, LSTMs and Linear critic), so that the towers
// and heads start as PPO's would from the seed.
inline constexpr uint64_t kRecurrentInitStream = 0x94d049bb133111ebULL;

}  // namespace rlrun
