#pragma once
// `--opponent` and `--side` of `rlrun eval` / `rlrun record` for the two-player game envs
// (TicTacToe-v0, ConnectFour-v0; docs/board_games.md): who plays the other side and which side
// the evaluated policy takes.
//   --opponent random | minimax | minimax:N | model:FILE
//   --side first | second | alternate | random
// random and minimax[:N] become the env's kwargs (env.kwargs.opponent, minimax_depth; and
// opponent_random_moves 0: the opponent plays as named, without the training's random moves);
// model:FILE (a model file or a checkpoint, e.g. a past self) plays as the env's self_play
// opponent: its deterministic graph up to the logits, sampled with the env's RNG
// (self_play_deterministic: true for its best move).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::cli {

struct GameOpponentOptions {
  std::string opponent;  // "" = the model's own env kwargs
  std::string side;
  std::string opponent_model() const;  // FILE of model:FILE, else ""
};

void add_game_opponent_options(CLI::App* sub, GameOpponentOptions& options);

// The --set overrides the options stand for (appended to `overrides`). Throws UsageError for
// a malformed --opponent.
void add_game_opponent_overrides(const GameOpponentOptions& options,
                                 std::vector<std::string>& overrides);

// With --opponent model:FILE: loads FILE (untrusted, spaces only: nothing it names runs) and
// hands it to `env` as a pool of one. Throws UsageError when `env` plays no pool opponent or the
// model does not fit the game.
void give_opponent_model(const GameOpponentOptions& options, Env& env, const Registry& registry);

}  // namespace rlrun::cli
