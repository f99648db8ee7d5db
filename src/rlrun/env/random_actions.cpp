#include "rlrun/env/random_actions.hpp"

#include <algorithm>
#include <cstdint>

namespace rlrun {

RandomActions::RandomActions(const Space& action_space)
    : space_(action_space), reader_(action_space) {}

void RandomActions::sample(const Info& info, int agents, Rng& rng, std::span<float> actions) {
  const size_t act_dim = static_cast<size_t>(space_.flat_dim());
  for (size_t a = 0; a < static_cast<size_t>(agents); ++a)
    space_.sample(rng, actions.subspan(a * act_dim, act_dim));
  if (!space_.is_discrete() || reader_.size() == 0) return;
  const size_t size = static_cast<size_t>(reader_.size());
  masks_.resize(size * static_cast<size_t>(agents));
  if (!reader_.read(info, agents, masks_).empty()) return;  // no (usable) mask reported
  for (size_t a = 0; a < static_cast<size_t>(agents); ++a) {
    const std::span<const float> mask(masks_.data() + a * size, size);
    uint64_t pick = rng.below(static_cast<uint64_t>(std::count(mask.begin(), mask.end(), 1.0f)));
    for (size_t k = 0; k < size; ++k)
      if (mask[k] == 1.0f && pick-- == 0) {
        actions[a] = static_cast<float>(space_.start() + static_cast<int64_t>(k));
        break;
      }
  }
}

}  // namespace rlrun
