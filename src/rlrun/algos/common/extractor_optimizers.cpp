#include "rlrun/algos/common/extractor_optimizers.hpp"

#include <string>

#include "rlrun/algos/common/training_state.hpp"

namespace rlrun {

namespace {
std::vector<SplitAdam> adams(FeaturesExtractorNet& extractor, ThreadPool* pool) {
  std::vector<SplitAdam> out;
  for (const ParamBlock& block : extractor.blocks()) out.emplace_back(block, AdamConfig{}, pool);
  return out;
}

void write_adams(StateWriter out, const std::string& name, const std::vector<SplitAdam>& adams) {
  for (size_t i = 0; i < adams.size(); ++i)
    for (int k = 0; k < 2; ++k)
      write_adam(out.sub(name + std::to_string(i) + "_" + std::to_string(k)), adams[i].part(k));
}

void read_adams(const StateReader& in, const std::string& name, std::vector<SplitAdam>& adams) {
  for (size_t i = 0; i < adams.size(); ++i)
    for (int k = 0; k < 2; ++k)
      read_adam(in.sub(name + std::to_string(i) + "_" + std::to_string(k)), adams[i].part(k));
}
}  // namespace

ExtractorOptimizers::ExtractorOptimizers(FeaturesExtractorNet& actor, FeaturesExtractorNet* critic,
                                         ThreadPool* pool)
    : actor_(adams(actor, pool)) {
  if (critic) critic_ = adams(*critic, pool);
}

void ExtractorOptimizers::step_actor(float lr) {
  for (SplitAdam& adam : actor_) adam.step(lr);
}

void ExtractorOptimizers::step_critic(float lr) {
  for (SplitAdam& adam : critic_) adam.step(lr);
}

void ExtractorOptimizers::write_state(StateWriter out) const {
  write_adams(out, "actor", actor_);
  write_adams(out, "critic", critic_);
}

void ExtractorOptimizers::read_state(const StateReader& in) {
  read_adams(in, "actor", actor_);
  read_adams(in, "critic", critic_);
}

}  // namespace rlrun
