#include "rlrun/envs/board_games/minimax_policy.hpp"

#include <memory>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/board_games/board_game_env.hpp"
#include "rlrun/envs/board_games/minimax_opponent.hpp"

namespace rlrun::board_games {

PolicyFn make_minimax_policy(Env& env, const PolicyOptions& options) {
  auto* game_env = dynamic_cast<BoardGameEnv*>(&env.unwrapped());
  if (!game_env) throw UsageError("the minimax policy plays the board games, not " + env.id());
  const BoardGameConfig& config = game_env->config();
  auto player = std::make_shared<MinimaxOpponent>(
      config.minimax_depth, config.minimax_ties == "first" ? MinimaxOpponent::Ties::kFirst
                                                           : MinimaxOpponent::Ties::kRandom);
  auto rng = std::make_shared<Rng>(options.seed);
  return [game_env, player, rng](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
    action.resize(1, obs.cols());
    const BoardPosition& position = game_env->position();
    action(0, 0) = static_cast<float>(player->choose(game_env->game(), position, *rng));
  };
}

}  // namespace rlrun::board_games
