#pragma once
// The player that moves inside a board-game env for the side the learner does not play (the
// single-agent view of a two-player game that SB3 self-play setups train on). An opponent is
// const and keeps no state between moves: its randomness comes from the env's Rng, so a game
// is a function of the env's seed, and copies of the env may step on several threads.
#include <string>

#include "rlrun/envs/board_games/board_game.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::board_games {

class Opponent {
 public:
  virtual ~Opponent() = default;
  virtual std::string name() const = 0;  // "random", "minimax depth 2"
  // The action for position.to_move in a position that is not over (it has a legal move).
  virtual int choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const = 0;
};

}  // namespace rlrun::board_games
