#pragma once
// The uniform random player: each legal move with equal probability, drawn from the env's Rng
// (PettingZoo's examples and tests play random legal moves: action_space.sample(mask)).
#include "rlrun/envs/board_games/opponent.hpp"

namespace rlrun::board_games {

class RandomOpponent : public Opponent {
 public:
  std::string name() const override { return "random"; }
  int choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const override;
};

}  // namespace rlrun::board_games
