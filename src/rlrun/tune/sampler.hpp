#pragma once
// A sampler as Optuna's BaseSampler (optuna/samplers/_base.py): at a trial's start the
// parameters it samples jointly ("relative": the search space every finished trial shared), then
// one by one those a trial asks for outside that space ("independent"). Values are in the
// internal representation (distribution.hpp).
//
// Reproducibility across workers: before a trial, the worker calls reseed(seed, trial number),
// so what a trial draws depends on the study's seed, its number and the trials before it — not
// on which process ran it or when.
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "rlrun/tune/frozen_trial.hpp"

namespace rlrun::tune {

using SearchSpace = std::map<std::string, Distribution>;

// The seed of one random stream of one trial: a hash of (study seed, stream, trial number), so
// that trial n's draws are the same whichever worker runs it, and neighbouring seeds or trial
// numbers give unrelated streams (SplitMix64's finaliser, as rlrun::Rng seeds itself).
inline uint64_t trial_seed(uint64_t seed, int trial_number, uint64_t stream) {
  auto mix = [](uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(seed ^ stream) + static_cast<uint64_t>(static_cast<int64_t>(trial_number)));
}

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual void reseed(uint64_t seed, int trial_number) = 0;
  // Optuna's infer_relative_search_space / sample_relative (empty for samplers without them).
  virtual SearchSpace infer_relative_search_space(const StudyView& study) = 0;
  virtual std::map<std::string, double> sample_relative(const StudyView& study,
                                                        const SearchSpace& space) = 0;
  virtual double sample_independent(const StudyView& study, const std::string& name,
                                    const Distribution& distribution) = 0;
};

}  // namespace rlrun::tune
