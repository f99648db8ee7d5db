#pragma once
// The sampler a study file's `sampler:` section names (tpe: Optuna's TPESampler as rl-zoo
// creates it; random: RandomSampler).
#include <memory>

#include "rlrun/tune/sampler.hpp"
#include "rlrun/tune/study_config.hpp"

namespace rlrun::tune {

std::unique_ptr<Sampler> make_sampler(const SamplerConfig& config);

}  // namespace rlrun::tune
