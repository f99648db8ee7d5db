#pragma once
// The rules of a two-player, turn-based board game on a grid of cells, as PettingZoo's classic
// games keep them (pettingzoo/classic/tictactoe/board.py, connect_four/connect_four.py): a flat
// board of cells, 0 empty, 1 a piece of the first player ("player_1" / "player_0", who moves
// first), 2 a piece of the second; one Discrete action per move. A BoardGame is stateless: it
// acts on a BoardPosition, so the env, the opponents and the minimax search share one rules
// object and copy positions freely.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rlrun::board_games {

enum class Outcome : int { kOngoing = 0, kFirstWins = 1, kSecondWins = 2, kDraw = 3 };

// The most cells of a game here (connect four's 6 x 7): positions are fixed-size values, so the
// minimax search copies them without allocating.
inline constexpr int kMaxCells = 42;

struct BoardPosition {
  std::array<int8_t, kMaxCells> cells{};  // 0 empty, 1 first player's piece, 2 second player's
  int to_move = 0;                        // 0: the first player moves next, 1: the second
  int moves_played = 0;
  Outcome outcome = Outcome::kOngoing;

  bool over() const { return outcome != Outcome::kOngoing; }
};

// The outcome "player `player` (0 or 1) won".
inline Outcome win_for(int player) {
  return player == 0 ? Outcome::kFirstWins : Outcome::kSecondWins;
}

// Where a cell is drawn: its row (0 at the top) and column.
struct CellPlace {
  int row = 0;
  int col = 0;
};

class BoardGame {
 public:
  virtual ~BoardGame() = default;

  virtual std::string name() const = 0;  // "TicTacToe-v0"
  virtual int num_cells() const = 0;
  virtual int num_actions() const = 0;
  // The observation's Box shape: (rows, cols, 2), PettingZoo's.
  virtual std::vector<int> observation_shape() const = 0;
  // The drawing's grid and where each cell sits on it.
  virtual int draw_rows() const = 0;
  virtual int draw_cols() const = 0;
  virtual CellPlace place_of(int cell) const = 0;
  // Pieces drawn as marks (tic-tac-toe's X and O) or as discs in a frame (connect four).
  virtual bool draws_marks() const = 0;

  // An action in [0, num_actions()) is legal when the game is not over and the move fits.
  virtual bool legal(const BoardPosition& position, int action) const = 0;
  // Plays a legal action for position.to_move, then sets the outcome and passes the turn.
  // Returns the cell the piece went to.
  virtual int play(BoardPosition& position, int action) const = 0;

  BoardPosition start() const;
  // The legal-move mask (1 legal, 0 not) of num_actions() entries: all 0 once the game is over
  // (PettingZoo's mask of an agent whose turn it is not).
  void write_mask(const BoardPosition& position, std::span<float> mask) const;
  std::vector<int> legal_actions(const BoardPosition& position) const;
  // PettingZoo's observe(agent): per cell, plane 0 = `perspective`'s piece, plane 1 = the other
  // player's, cells in the board's flat order (obs index = cell * 2 + plane).
  void write_planes(const BoardPosition& position, int perspective, std::span<float> obs) const;
  // Whether `cells` (the first num_cells(); the rest 0) fit `to_move` and `moves_played` (piece
  // counts match the turn); used to check restored state.
  bool plausible(const BoardPosition& position) const;
};

}  // namespace rlrun::board_games
