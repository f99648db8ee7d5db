#pragma once
// `--policy minimax` / `--baseline minimax` for the board-game envs: the learner's side played
// by a minimax player with the env's own settings (minimax_depth, minimax_ties). It reads the
// position from the env it is made for (the board its observation shows); ties draw from a Rng
// seeded by --seed.
#include "rlrun/env.hpp"
#include "rlrun/env/policy.hpp"

namespace rlrun::board_games {

// Throws UsageError when `env` is not a board-game env.
PolicyFn make_minimax_policy(Env& env, const PolicyOptions& options);

}  // namespace rlrun::board_games
