#include "rlrun/algos/common/extractor_optimizers.hpp"

#include <string>

#include "rlrun/algos/common/training_state.hpp"

namespace rlrun {

ExtractorOptimizers::ExtractorOptimizers(FeaturesExtractorNet& actor, FeaturesExtractorNet& critic,
                                         ThreadPool* pool)
    : active_(actor.learned()) {
  if (!active_) return;
  actor_ = SplitAdam(actor.block(), AdamConfig{}, pool);
  critic_ = SplitAdam(critic.block(), AdamConfig{}, pool);
}

void ExtractorOptimizers::write_state(StateWriter out) const {
  for (int k = 0; k < 2; ++k) {
    write_adam(out.sub("actor" + std::to_string(k)), actor_.part(k));
    write_adam(out.sub("critic" + std::to_string(k)), critic_.part(k));
  }
}

void ExtractorOptimizers::read_state(const StateReader& in) {
  for (int k = 0; k < 2; ++k) {
    read_adam(in.sub("actor" + std::to_string(k)), actor_.part(k));
    read_adam(in.sub("critic" + std::to_string(k)), critic_.part(k));
  }
}

}  // namespace rlrun
