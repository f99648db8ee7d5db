// The rules of TicTacToe-v0 and ConnectFour-v0 against PettingZoo classic's
// (pettingzoo/classic/tictactoe/board.py, connect_four/connect_four.py): every winning line,
// draws, illegal moves, masks and the observation planes of hand-computed boards.
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/envs/board_games/connect_four.hpp"
#include "rlrun/envs/board_games/tic_tac_toe.hpp"

using namespace rlrun::board_games;

namespace {

using Vec = std::vector<float>;

BoardPosition play_all(const BoardGame& game, const std::vector<int>& moves) {
  BoardPosition position = game.start();
  for (int move : moves) {
    REQUIRE_FALSE(position.over());
    game.play(position, move);
  }
  return position;
}

// board.py's eight lines.
const std::vector<std::vector<int>> kTicTacToeLines{{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {0, 3, 6},
                                                    {1, 4, 7}, {2, 5, 8}, {0, 4, 8}, {2, 4, 6}};

bool on_a_line(const std::vector<int>& cells) {
  for (const auto& line : kTicTacToeLines) {
    int n = 0;
    for (int c : line)
      for (int x : cells) n += c == x;
    if (n == 3) return true;
  }
  return false;
}

// Three squares off `line` that hold no line themselves (the loser's moves).
std::vector<int> three_off(const std::vector<int>& line) {
  std::vector<int> off;
  for (int s = 0; s < 9; ++s)
    if (std::find(line.begin(), line.end(), s) == line.end()) off.push_back(s);
  for (size_t a = 0; a < off.size(); ++a)
    for (size_t b = a + 1; b < off.size(); ++b)
      for (size_t c = b + 1; c < off.size(); ++c)
        if (!on_a_line({off[a], off[b], off[c]})) return {off[a], off[b], off[c]};
  return {};
}

}  // namespace

TEST_CASE("tic-tac-toe: each of the eight lines wins for either player", "[board_games]") {
  TicTacToe game;
  for (const auto& line : kTicTacToeLines) {
    const std::vector<int> other = three_off(line);
    REQUIRE(other.size() == 3);
    // The first player takes the line; the game ends on its third mark.
    BoardPosition first = play_all(game, {line[0], other[0], line[1], other[1]});
    CHECK_FALSE(first.over());
    game.play(first, line[2]);
    CHECK(first.outcome == Outcome::kFirstWins);
    // The second player takes it while the first plays three squares off it.
    BoardPosition second = play_all(game, {other[0], line[0], other[1], line[1], other[2]});
    CHECK_FALSE(second.over());
    game.play(second, line[2]);
    CHECK(second.outcome == Outcome::kSecondWins);
    CHECK(second.moves_played == 6);
  }
}

TEST_CASE("tic-tac-toe: a full board without a line is a draw", "[board_games]") {
  TicTacToe game;
  // X: 0 8 7 2 3, O: 4 1 6 5 -- no line of either (checked line by line by hand).
  const BoardPosition position = play_all(game, {0, 4, 8, 1, 7, 6, 2, 5, 3});
  CHECK(position.outcome == Outcome::kDraw);
  Vec mask(9, 1.0f);
  game.write_mask(position, mask);
  CHECK(mask == Vec(9, 0.0f));
}

TEST_CASE("tic-tac-toe: masks, illegal moves and the observation planes", "[board_games]") {
  TicTacToe game;
  BoardPosition position = play_all(game, {0, 4, 5});  // X 0, O 4, X 5; O to move
  CHECK(position.to_move == 1);
  Vec mask(9);
  game.write_mask(position, mask);
  CHECK(mask == Vec{0, 1, 1, 1, 0, 0, 1, 1, 1});
  CHECK_FALSE(game.legal(position, 4));
  CHECK_FALSE(game.legal(position, 9));
  CHECK_FALSE(game.legal(position, -1));
  CHECK_THROWS_AS(game.play(position, 0), std::logic_error);
  // observe(): square k at [k / 3][k % 3][plane]; flat index 2k + plane.
  Vec seen_by_o(18), seen_by_x(18);
  game.write_planes(position, 1, seen_by_o);
  game.write_planes(position, 0, seen_by_x);
  CHECK(seen_by_o == Vec{0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0});
  CHECK(seen_by_x == Vec{1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0});
  // Drawn down the columns: square 5 is row 2, column 1 (board.py's 0 3 6 / 1 4 7 / 2 5 8).
  CHECK(game.place_of(5).row == 2);
  CHECK(game.place_of(5).col == 1);
}

TEST_CASE("connect four: pieces fall, full columns are illegal", "[board_games]") {
  ConnectFour game;
  BoardPosition position = game.start();
  CHECK(game.play(position, 3) == 5 * 7 + 3);  // the bottom row
  CHECK(game.play(position, 3) == 4 * 7 + 3);
  for (int i = 0; i < 4; ++i) game.play(position, 3);
  CHECK(position.cells[3] == 2);  // the sixth piece, the second player's, at the top
  CHECK_FALSE(position.over());
  Vec mask(7);
  game.write_mask(position, mask);
  CHECK(mask == Vec{1, 1, 1, 0, 1, 1, 1});
  CHECK_FALSE(game.legal(position, 3));
  CHECK_FALSE(game.legal(position, 7));
  CHECK_THROWS_AS(game.play(position, 3), std::logic_error);
  // The planes of the first player: its pieces at rows 5, 3, 1 of column 3.
  Vec planes(84);
  game.write_planes(position, 0, planes);
  for (int row = 0; row < 6; ++row) {
    const int cell = row * 7 + 3;
    CHECK(planes[2 * cell] == (row % 2 == 1 ? 1.0f : 0.0f));
    CHECK(planes[2 * cell + 1] == (row % 2 == 0 ? 1.0f : 0.0f));
  }
  float total = 0;
  for (float v : planes) total += v;
  CHECK(total == 6);
}

TEST_CASE("connect four: every four-cell window is a win, three of it is not", "[board_games]") {
  ConnectFour game;
  int windows = 0;
  constexpr int kDirections[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 7; ++col)
      for (const auto& d : kDirections) {
        const int end_row = row + 3 * d[0], end_col = col + 3 * d[1];
        if (end_row < 0 || end_row >= 6 || end_col < 0 || end_col >= 7) continue;
        ++windows;
        BoardPosition position = game.start();
        for (int i = 0; i < 4; ++i) position.cells[(row + i * d[0]) * 7 + col + i * d[1]] = 2;
        for (int i = 0; i < 4; ++i)
          CHECK(ConnectFour::completes_four(position, (row + i * d[0]) * 7 + col + i * d[1]));
        position.cells[row * 7 + col] = 1;  // three of the window, the fourth the other's
        CHECK_FALSE(ConnectFour::completes_four(position, (row + d[0]) * 7 + col + d[1]));
      }
  CHECK(windows == 69);  // 24 horizontal, 21 vertical, 12 + 12 diagonal
}

TEST_CASE("connect four: wins in play and a drawn full board", "[board_games]") {
  ConnectFour game;
  // Horizontal: the first player on the bottom row, columns 0-3.
  CHECK(play_all(game, {0, 0, 1, 1, 2, 2, 3}).outcome == Outcome::kFirstWins);
  // Vertical: the second player stacks column 6.
  CHECK(play_all(game, {0, 6, 1, 6, 0, 6, 1, 6}).outcome == Outcome::kSecondWins);
  // Rising diagonal, (row, column) from the top: (5,0) (4,1) (3,2) (2,3), the first player's.
  CHECK(play_all(game, {0, 1, 1, 2, 2, 3, 2, 3, 3, 6, 3}).outcome == Outcome::kFirstWins);
  // The other diagonal: (5,3) (4,2) (3,1) (2,0), the first player's.
  CHECK(play_all(game, {3, 2, 2, 1, 1, 0, 1, 0, 0, 6, 0}).outcome == Outcome::kFirstWins);
  // 42 moves, no four (found by a search and checked by these rules): a draw.
  const BoardPosition full =
      play_all(game, {6, 4, 6, 2, 3, 0, 0, 2, 1, 6, 6, 2, 4, 6, 4, 5, 3, 6, 1, 5, 1,
                      3, 0, 5, 2, 1, 2, 0, 2, 3, 5, 4, 1, 1, 4, 3, 5, 4, 3, 5, 0, 0});
  CHECK(full.outcome == Outcome::kDraw);
  CHECK(full.moves_played == 42);
  CHECK(game.legal_actions(full).empty());
}
