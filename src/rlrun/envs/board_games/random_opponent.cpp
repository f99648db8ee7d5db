#include "rlrun/envs/board_games/random_opponent.hpp"

#include <stdexcept>

namespace rlrun::board_games {

int RandomOpponent::choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const {
  const std::vector<int> legal = game.legal_actions(position);
  if (legal.empty()) throw std::logic_error(game.name() + ": the random player has no legal move");
  return legal[static_cast<size_t>(rng.below(legal.size()))];
}

}  // namespace rlrun::board_games
