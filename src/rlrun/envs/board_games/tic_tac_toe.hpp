#pragma once
// Tic-tac-toe with PettingZoo's rules and layout (pettingzoo/classic/tictactoe/board.py,
// tictactoe.py, tictactoe-v3). Action k marks square k; squares are numbered down the columns,
//     0 | 3 | 6
//     1 | 4 | 7
//     2 | 5 | 8
// (board.py's comment and render()), and the observation is squares reshaped to (3, 3, 2) with
// square k at [k / 3][k % 3] (observe(): np.array(squares).reshape(3, 3)). Three marks in one of
// the eight lines win; a full board without a line is a draw.
#include "rlrun/envs/board_games/board_game.hpp"

namespace rlrun::board_games {

class TicTacToe : public BoardGame {
 public:
  static constexpr int kSquares = 9;

  std::string name() const override { return "TicTacToe-v0"; }
  int num_cells() const override { return kSquares; }
  int num_actions() const override { return kSquares; }
  std::vector<int> observation_shape() const override { return {3, 3, 2}; }
  int draw_rows() const override { return 3; }
  int draw_cols() const override { return 3; }
  // Square k is drawn in column k / 3, row k % 3 (render(): x = mark_pos / 3, y = mark_pos % 3).
  CellPlace place_of(int cell) const override { return {cell % 3, cell / 3}; }

  bool draws_marks() const override { return true; }

  bool legal(const BoardPosition& position, int action) const override;
  int play(BoardPosition& position, int action) const override;
};

}  // namespace rlrun::board_games
