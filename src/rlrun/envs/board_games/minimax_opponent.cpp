#include "rlrun/envs/board_games/minimax_opponent.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rlrun::board_games {

int negamax(const BoardGame& game, const BoardPosition& position, int depth, int ply, int alpha,
            int beta) {
  if (position.over()) {
    if (position.outcome == Outcome::kDraw) return 0;
    // The player who just moved won: a loss for the player to move, worse the sooner.
    return -(MinimaxOpponent::kWin - ply);
  }
  if (depth == 0) return 0;
  int best = -2 * MinimaxOpponent::kWin;
  for (int action = 0; action < game.num_actions(); ++action) {
    if (!game.legal(position, action)) continue;
    BoardPosition child = position;
    game.play(child, action);
    const int score = -negamax(game, child, depth - 1, ply + 1, -beta, -alpha);
    best = std::max(best, score);
    alpha = std::max(alpha, score);
    if (alpha >= beta) break;  // the opponent will not allow this line
  }
  return best;
}

MinimaxOpponent::MinimaxOpponent(int depth, Ties ties) : depth_(depth), ties_(ties) {
  if (depth < 1) throw std::invalid_argument("minimax depth must be >= 1");
}

std::string MinimaxOpponent::name() const { return "minimax depth " + std::to_string(depth_); }

std::vector<int> MinimaxOpponent::action_scores(const BoardGame& game,
                                                const BoardPosition& position) const {
  std::vector<int> scores(static_cast<size_t>(game.num_actions()), -2 * kWin);
  for (int action = 0; action < game.num_actions(); ++action) {
    if (!game.legal(position, action)) continue;
    BoardPosition child = position;
    game.play(child, action);
    // A full window per root move: each move's exact score, so equal moves are found as ties.
    scores[action] = -negamax(game, child, depth_ - 1, 1, -2 * kWin, 2 * kWin);
  }
  return scores;
}

int MinimaxOpponent::choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const {
  const std::vector<int> scores = action_scores(game, position);
  const int best = *std::max_element(scores.begin(), scores.end());
  std::vector<int> tied;
  for (int action = 0; action < game.num_actions(); ++action)
    if (game.legal(position, action) && scores[action] == best) tied.push_back(action);
  if (tied.empty()) throw std::logic_error(game.name() + ": minimax has no legal move");
  if (ties_ == Ties::kFirst || tied.size() == 1) return tied.front();
  return tied[static_cast<size_t>(rng.below(tied.size()))];
}

}  // namespace rlrun::board_games
