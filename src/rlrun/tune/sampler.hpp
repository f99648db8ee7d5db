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
