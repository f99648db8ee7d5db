#include "rlrun/algos/common/resumable_algorithm.hpp"

#include <utility>

namespace rlrun {

void ResumableAlgorithm::checkpoint(std::function<void(StateWriter&)> write,
                                    std::function<void(const StateReader&)> read) {
  write_items_.push_back(std::move(write));
  read_items_.push_back(std::move(read));
}

void ResumableAlgorithm::save_training_state(StateWriter& out) const {
  for (const auto& write : write_items_) write(out);
}

void ResumableAlgorithm::load_training_state(const StateReader& in) {
  for (const auto& read : read_items_) read(in);
}

}  // namespace rlrun
