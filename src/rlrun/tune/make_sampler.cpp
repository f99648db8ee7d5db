#include "rlrun/tune/make_sampler.hpp"

#include "rlrun/tune/random_sampler.hpp"
#include "rlrun/tune/tpe_sampler.hpp"

namespace rlrun::tune {

std::unique_ptr<Sampler> make_sampler(const SamplerConfig& config) {
  const uint64_t seed = config.seed.value_or(0);
  if (config.type == "random") return std::make_unique<RandomSampler>(seed);
  TpeConfig tpe;
  tpe.n_startup_trials = config.n_startup_trials;
  tpe.n_ei_candidates = config.n_ei_candidates;
  tpe.multivariate = config.multivariate;
  return std::make_unique<TpeSampler>(tpe, seed);
}

}  // namespace rlrun::tune
