#pragma once
// The one way an algorithm lists its training state for an exact resume (what
// Algorithm::save_training_state must hold beyond the model tensors: counters, RNG streams,
// optimizer moments, gSDE's exploration matrices, rollout and replay buffers). Each item is
// registered once, in the constructor, with checkpoint(key, item); save_training_state writes
// every item under its key and load_training_state reads every item back. Both algorithm
// families derive from it: OnPolicyAlgorithm (on_policy.hpp) and OffPolicyAlgorithm
// (off_policy.hpp), so a new member of the training state is one checkpoint() line beside the
// member it saves.
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/common/training_state.hpp"

namespace rlrun {

class ResumableAlgorithm : public Algorithm {
 public:
  // Optimizers and checkpoint items point into members: no copies or moves.
  ResumableAlgorithm(const ResumableAlgorithm&) = delete;
  ResumableAlgorithm& operator=(const ResumableAlgorithm&) = delete;

  void save_training_state(StateWriter& out) const final;
  void load_training_state(const StateReader& in) final;

 protected:
  ResumableAlgorithm() = default;

  // Adds `item` to the training state under `key`: an Rng, an int64_t or double counter, an
  // Adam or RmsProp optimizer, gSDE's StateDependentNoise, or a component with
  // write_state(StateWriter) and read_state(const StateReader&). It must stay where it is (a
  // member built before this call).
  template <class T>
  void checkpoint(const std::string& key, T& item);
  // An item with a layout of its own (the off-policy replay state, present only once a buffer
  // exists): how it is written and read back.
  void checkpoint(std::function<void(StateWriter&)> write,
                  std::function<void(const StateReader&)> read);

 private:
  std::vector<std::function<void(StateWriter&)>> write_items_;
  std::vector<std::function<void(const StateReader&)>> read_items_;
};

template <class T>
void ResumableAlgorithm::checkpoint(const std::string& key, T& item) {
  if constexpr (std::is_same_v<T, Rng>) {
    checkpoint([key, &item](StateWriter& out) { out.put_rng(key, item); },
               [key, &item](const StateReader& in) { in.get_rng(key, item); });
  } else if constexpr (std::is_same_v<T, int64_t>) {
    // Counters (num_timesteps, n_updates, ...): never negative.
    checkpoint([key, &item](StateWriter& out) { out.put_int(key, item); },
               [key, &item](const StateReader& in) { item = in.get_count(key); });
  } else if constexpr (std::is_same_v<T, double>) {
    checkpoint([key, &item](StateWriter& out) { out.put_double(key, item); },
               [key, &item](const StateReader& in) { item = in.get_double(key); });
  } else if constexpr (std::is_same_v<T, Adam>) {
    checkpoint([key, &item](StateWriter& out) { write_adam(out.sub(key), item); },
               [key, &item](const StateReader& in) { read_adam(in.sub(key), item); });
  } else if constexpr (std::is_same_v<T, RmsProp>) {
    checkpoint([key, &item](StateWriter& out) { write_rmsprop(out.sub(key), item); },
               [key, &item](const StateReader& in) { read_rmsprop(in.sub(key), item); });
  } else if constexpr (std::is_same_v<T, StateDependentNoise>) {
    checkpoint([key, &item](StateWriter& out) { write_sde(out.sub(key), item); },
               [key, &item](const StateReader& in) { read_sde(in.sub(key), item); });
  } else {
    checkpoint([key, &item](StateWriter& out) { item.write_state(out.sub(key)); },
               [key, &item](const StateReader& in) { item.read_state(in.sub(key)); });
  }
}

}  // namespace rlrun
