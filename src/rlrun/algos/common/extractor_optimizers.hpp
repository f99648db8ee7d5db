#pragma once
// The optimizers of an off-policy CnnPolicy's two learned features extractors (SAC, TQC, TD3,
// DDPG: the actor's NatureCNN and the critic's, features_extractor_net.hpp). SB3 puts each in
// its module's one Adam (actor.optimizer over actor.parameters(), critic.optimizer over
// critic.parameters()); Adam is element-wise with one step count per optimizer, so an Adam of
// their own, stepped with the same learning rate right after the module's, is the same update.
// Each network's is a SplitAdam: the 1.7 M parameters of an 84x84 NatureCNN are stepped on the
// run's threads.
#include <vector>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/split_adam.hpp"

namespace rlrun {

class ExtractorOptimizers {
 public:
  ExtractorOptimizers() = default;
  // An Adam for each network of the two extractors (none for flatten extractors; none for the
  // critic's when it shares the actor's: `critic` null).
  ExtractorOptimizers(FeaturesExtractorNet& actor, FeaturesExtractorNet* critic, ThreadPool* pool);

  // Whether there is anything to step (a CnnPolicy), and so anything to checkpoint.
  bool active() const { return !actor_.empty() || !critic_.empty(); }
  // One Adam step of the actor's / the critic's extractor from its grads().
  void step_actor(float lr);
  void step_critic(float lr);

  // Exact resume: every Adam's moments and step count.
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);

 private:
  std::vector<SplitAdam> actor_, critic_;
};

}  // namespace rlrun
