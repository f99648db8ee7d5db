// The minimax opponent: it takes a win, blocks one, prefers the quickest win, is a perfect
// tic-tac-toe player at full depth (it never loses, and against itself every game is a draw),
// and its tie rule is reproducible.
#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/envs/board_games/connect_four.hpp"
#include "rlrun/envs/board_games/minimax_opponent.hpp"
#include "rlrun/envs/board_games/random_opponent.hpp"
#include "rlrun/envs/board_games/tic_tac_toe.hpp"

using namespace rlrun;
using namespace rlrun::board_games;

namespace {

BoardPosition play_all(const BoardGame& game, const std::vector<int>& moves) {
  BoardPosition position = game.start();
  for (int move : moves) game.play(position, move);
  return position;
}

// One game between two players from the start; returns the outcome.
Outcome play_game(const BoardGame& game, const Opponent& first, const Opponent& second, Rng& rng) {
  BoardPosition position = game.start();
  while (!position.over())
    game.play(position, (position.to_move == 0 ? first : second).choose(game, position, rng));
  return position.outcome;
}

}  // namespace

TEST_CASE("minimax: takes a win and blocks a loss", "[board_games]") {
  TicTacToe game;
  Rng rng(1);
  // X 0, O 4, X 1: X threatens 2 (line 0 1 2). O to move must block at 2.
  const BoardPosition threat = play_all(game, {0, 4, 1});
  CHECK(MinimaxOpponent(2, MinimaxOpponent::Ties::kRandom).choose(game, threat, rng) == 2);
  // X 0, O 3, X 1, O 4: X to move wins at 2 (and O threatens 5).
  const BoardPosition win = play_all(game, {0, 3, 1, 4});
  const MinimaxOpponent one_ply(1, MinimaxOpponent::Ties::kFirst);
  CHECK(one_ply.choose(game, win, rng) == 2);
  const std::vector<int> scores = one_ply.action_scores(game, win);
  CHECK(scores[2] == MinimaxOpponent::kWin - 1);
  CHECK(scores[5] == 0);                           // the horizon: no win seen in one ply
  CHECK(scores[0] == -2 * MinimaxOpponent::kWin);  // taken
  // Connect four: the second player has three in column 6; depth 2 blocks, depth 1 plays its
  // lowest tied move.
  ConnectFour four;
  const BoardPosition stack = play_all(four, {0, 6, 1, 6, 3, 6});
  CHECK(MinimaxOpponent(1, MinimaxOpponent::Ties::kFirst).choose(four, stack, rng) == 2);
  CHECK(MinimaxOpponent(2, MinimaxOpponent::Ties::kFirst).choose(four, stack, rng) == 2);
  // ...and the first player has 0 1 _ 3 on the bottom row: 2 wins at once.
  CHECK(MinimaxOpponent(2, MinimaxOpponent::Ties::kRandom).choose(four, stack, rng) == 2);
  const BoardPosition must_block = play_all(four, {0, 6, 1, 6, 5, 6});
  CHECK(MinimaxOpponent(2, MinimaxOpponent::Ties::kRandom).choose(four, must_block, rng) == 6);
}

TEST_CASE("minimax: the quickest forced win scores highest", "[board_games]") {
  TicTacToe game;
  // X 0, O 1, X 4: X threatens 8. Every O move but 8 loses at X's next move (ply 2); after 8,
  // X forks (6 or 3) and wins at ply 4: O's best, the later loss, is 8.
  const BoardPosition position = play_all(game, {0, 1, 4});
  const std::vector<int> scores =
      MinimaxOpponent(9, MinimaxOpponent::Ties::kFirst).action_scores(game, position);
  for (int a : {2, 3, 5, 6, 7}) CHECK(scores[a] == -(MinimaxOpponent::kWin - 2));
  CHECK(scores[8] == -(MinimaxOpponent::kWin - 4));
}

TEST_CASE("minimax: full-depth tic-tac-toe is perfect play", "[board_games]") {
  TicTacToe game;
  const MinimaxOpponent perfect(9, MinimaxOpponent::Ties::kRandom);
  const RandomOpponent random;
  // The empty board is a draw with best play from both sides.
  for (int score : perfect.action_scores(game, game.start())) CHECK(score <= 0);
  Rng rng(7);
  for (int i = 0; i < 20; ++i) CHECK(play_game(game, perfect, perfect, rng) == Outcome::kDraw);
  for (int i = 0; i < 50; ++i) {
    CHECK(play_game(game, perfect, random, rng) != Outcome::kSecondWins);
    CHECK(play_game(game, random, perfect, rng) != Outcome::kFirstWins);
  }
}

TEST_CASE("minimax: ties are reproducible for a seed", "[board_games]") {
  ConnectFour game;
  const MinimaxOpponent player(2, MinimaxOpponent::Ties::kRandom);
  const MinimaxOpponent first(2, MinimaxOpponent::Ties::kFirst);
  Rng a(3), b(3), c(4);
  std::vector<int> moves_a, moves_b, moves_c;
  for (int i = 0; i < 10; ++i) {
    moves_a.push_back(player.choose(game, game.start(), a));
    moves_b.push_back(player.choose(game, game.start(), b));
    moves_c.push_back(player.choose(game, game.start(), c));
    CHECK(first.choose(game, game.start(), c) == 0);  // every opening ties at depth 2
  }
  CHECK(moves_a == moves_b);
  CHECK(moves_a != moves_c);
}
