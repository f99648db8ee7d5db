// rlrun._core.BoardGame: both seats of a built-in board game (TicTacToe-v0, ConnectFour-v0)
// played from Python, one move at a time for whichever player is to move — no opponent inside,
// unlike the single-agent env of the same id. python/rlrun/_board_games.py shapes it into
// PettingZoo's AEC API (rlrun.env("TicTacToe-v0")), as PettingZoo classic's tictactoe_v3 and
// connect_four_v3. The rules, planes and masks are the env's own (src/rlrun/envs/board_games/).
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "rlrun/envs/board_games/board_drawing.hpp"
#include "rlrun/envs/board_games/board_game_envs.hpp"

namespace rlrun::python {

namespace {

using board_games::BoardGame;
using board_games::BoardPosition;

class PyBoardGame {
 public:
  explicit PyBoardGame(const std::string& id) : game_(board_games::board_game_rules(id)), id_(id) {
    if (!game_)
      throw py::value_error("'" + id +
                            "' is not a two-player board game (TicTacToe-v0, ConnectFour-v0)");
    position_ = game_->start();
  }

  void reset() { position_ = game_->start(); }

  // Plays `action` for the player to move; a ValueError (nothing changes) when it is not legal.
  void play(int action) {
    if (position_.over()) throw py::value_error(id_ + ": the game is over");
    if (action < 0 || action >= game_->num_actions() || !game_->legal(position_, action)) {
      std::string legal;
      for (int a : game_->legal_actions(position_))
        legal += (legal.empty() ? "" : ", ") + std::to_string(a);
      throw py::value_error(id_ + ": " + std::to_string(action) +
                            " is not a legal move (legal: " + legal + ")");
    }
    game_->play(position_, action);
  }

  // The legal moves of the player to move (1 legal, 0 not), int8. With `after_end` the moves
  // that fit the board even once the game is over (empty squares, open columns), as PettingZoo's
  // observe() masks the agent selected after the final move; else all 0 then.
  py::array_t<int8_t> legal_mask(bool after_end) const {
    BoardPosition position = position_;
    if (after_end) position.outcome = board_games::Outcome::kOngoing;
    std::vector<float> mask(static_cast<size_t>(game_->num_actions()));
    game_->write_mask(position, mask);
    py::array_t<int8_t> out(static_cast<py::ssize_t>(mask.size()));
    for (size_t i = 0; i < mask.size(); ++i) out.mutable_data()[i] = mask[i] != 0.0f ? 1 : 0;
    return out;
  }

  // PettingZoo's observe(agent) planes for `perspective` (0 first player, 1 second), int8 of the
  // observation's shape.
  py::array_t<int8_t> planes(int perspective) const {
    if (perspective != 0 && perspective != 1) throw py::value_error("perspective is 0 or 1");
    const std::vector<int> shape = game_->observation_shape();
    std::vector<float> obs(static_cast<size_t>(game_->num_cells()) * 2);
    game_->write_planes(position_, perspective, obs);
    py::array_t<int8_t> out(std::vector<py::ssize_t>(shape.begin(), shape.end()));
    for (size_t i = 0; i < obs.size(); ++i) out.mutable_data()[i] = static_cast<int8_t>(obs[i]);
    return out;
  }

  // The board as an (H, W, 3) uint8 picture.
  py::array_t<uint8_t> render() {
    const RenderSpec spec = board_games::board_render_spec(*game_);
    if (!frame_) frame_ = std::make_unique<Frame>(spec.width, spec.height);
    board_games::draw_board(*game_, position_, *frame_);
    frame_->to_rgb(rgb_);
    py::array_t<uint8_t> out({spec.height, spec.width, 3});
    std::copy(rgb_.begin(), rgb_.end(), out.mutable_data());
    return out;
  }

  std::unique_ptr<const BoardGame> game_;
  std::string id_;
  BoardPosition position_;
  std::unique_ptr<Frame> frame_;
  std::vector<uint8_t> rgb_;
};

}  // namespace

void bind_board_game(py::module_& m) {
  py::class_<PyBoardGame>(m, "BoardGame")
      .def(py::init<const std::string&>(), py::arg("id"))
      .def("reset", &PyBoardGame::reset)
      .def("play", &PyBoardGame::play, py::arg("action"))
      .def("legal_mask", &PyBoardGame::legal_mask, py::arg("after_end") = false)
      .def("planes", &PyBoardGame::planes, py::arg("perspective"))
      .def("render", &PyBoardGame::render)
      .def_property_readonly("id", [](const PyBoardGame& g) { return g.id_; })
      .def_property_readonly("num_actions",
                             [](const PyBoardGame& g) { return g.game_->num_actions(); })
      .def_property_readonly("observation_shape",
                             [](const PyBoardGame& g) { return g.game_->observation_shape(); })
      .def_property_readonly("to_move", [](const PyBoardGame& g) { return g.position_.to_move; })
      .def_property_readonly("moves_played",
                             [](const PyBoardGame& g) { return g.position_.moves_played; })
      // 0 ongoing, 1 the first player won, 2 the second, 3 a draw.
      .def_property_readonly(
          "outcome", [](const PyBoardGame& g) { return static_cast<int>(g.position_.outcome); })
      .def_property_readonly("render_fps", [](const PyBoardGame& g) {
        return board_games::board_render_spec(*g.game_).fps;
      });
  m.def("board_game_ids", &board_games::board_game_ids);
}

}  // namespace rlrun::python
