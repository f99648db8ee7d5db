// TicTacToe-v0 and ConnectFour-v0 as envs: the learner's view (planes, masks, rewards), the
// opponent's opening when the learner plays second, sides per episode, illegal moves,
// reproducibility for a seed, exact resume, refused states, kwargs, drawing.
#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/board_games/board_game_envs.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/builtins.hpp"

using namespace rlrun;
using namespace rlrun::board_games;

namespace {

using Vec = std::vector<float>;

StepResult act(Env& env, int action, Vec& obs) {
  const float a = static_cast<float>(action);
  return env.step({&a, 1}, obs);
}

double info_of(const Env& env, const char* key) { return env.info().get(env.info().find(key)); }

Vec mask_of(const Env& env, int n) {
  Vec mask;
  for (int a = 0; a < n; ++a)
    mask.push_back(static_cast<float>(info_of(env, ("action_mask." + std::to_string(a)).c_str())));
  return mask;
}

TicTacToeEnv::Config tic_tac_toe_config(const char* side, const char* opponent = "random") {
  TicTacToeEnv::Config config;
  config.learner_side = side;
  config.opponent = opponent;
  config.minimax_ties = "first";
  return config;
}

}  // namespace

TEST_CASE("board game env: spaces, registration and the learner moving first", "[board_games]") {
  TicTacToeEnv env(tic_tac_toe_config("first"));
  CHECK(env.id() == "TicTacToe-v0");
  CHECK(env.observation_space().describe() == "Box(0.0, 1.0, (3, 3, 2), float32)");
  CHECK(env.action_space().describe() == "Discrete(9)");
  ConnectFourEnv four;
  CHECK(four.observation_space().describe() == "Box(0.0, 1.0, (6, 7, 2), float32)");
  CHECK(four.action_space().describe() == "Discrete(7)");
  CHECK(four.config().minimax_depth == 2);
  CHECK(env.config().minimax_depth == 9);
  for (const char* id : {"TicTacToe-v0", "ConnectFour-v0"}) {
    const EnvEntry* entry = builtin_registry().find_env(id);
    REQUIRE(entry != nullptr);
    CHECK(entry->max_episode_steps == 0);
    CHECK(entry->metrics == std::vector<std::string>{"win", "draw", "loss"});
  }
  Vec obs(18, 5.0f);
  env.reset(1, obs);
  CHECK(obs == Vec(18, 0.0f));
  CHECK(mask_of(env, 9) == Vec(9, 1.0f));
  CHECK(info_of(env, "learner_first") == 1.0);
  const StepResult s = act(env, 4, obs);
  CHECK(s.reward == 0.0);
  CHECK_FALSE(s.terminated);
  // The learner's X in plane 0 at square 4, the random opponent's O somewhere in plane 1.
  CHECK(obs[2 * 4] == 1.0f);
  float opponent = 0;
  for (int k = 0; k < 9; ++k) opponent += obs[2 * k + 1];
  CHECK(opponent == 1.0f);
  CHECK(env.position().moves_played == 2);
}

TEST_CASE("board game env: the learner second sees the opponent's opening as plane 1",
          "[board_games]") {
  // minimax with ties "first" opens tic-tac-toe at square 0 (every opening draws).
  TicTacToeEnv env(tic_tac_toe_config("second", "minimax"));
  Vec obs(18);
  env.reset(0, obs);
  Vec expected(18, 0.0f);
  expected[1] = 1.0f;  // square 0, plane 1: the opponent's
  CHECK(obs == expected);
  CHECK(info_of(env, "learner_first") == 0.0);
  CHECK(mask_of(env, 9) == Vec{0, 1, 1, 1, 1, 1, 1, 1, 1});
  CHECK(env.position().to_move == 1);
}

TEST_CASE("board game env: wins, losses and illegal moves", "[board_games]") {
  SECTION("the learner wins against a minimax that sees one ply") {
    TicTacToeEnv::Config config = tic_tac_toe_config("first", "minimax");
    config.minimax_depth = 1;  // plays its lowest free square, never blocks
    TicTacToeEnv env(config);
    Vec obs(18);
    env.reset(0, obs);
    StepResult s;
    for (int move : {2, 5, 8}) s = act(env, move, obs);  // O: 0, 1; X: 2 5 8
    CHECK(s.reward == 1.0);
    CHECK(s.terminated);
    CHECK(info_of(env, "win") == 1.0);
    CHECK(info_of(env, "loss") == 0.0);
    CHECK(mask_of(env, 9) == Vec(9, 0.0f));
    CHECK_THROWS_AS(act(env, 3, obs), std::logic_error);
  }
  SECTION("the learner loses to perfect play") {
    // X always takes its lowest free square: X 0, O 4, X 1, O 2 (blocks), X 3, O 6 wins (2 4 6).
    TicTacToeEnv env(tic_tac_toe_config("first", "minimax"));
    Vec obs(18);
    env.reset(0, obs);
    StepResult s;
    while (!s.terminated) {
      int move = 0;
      while (!env.game().legal(env.position(), move)) ++move;
      s = act(env, move, obs);
    }
    CHECK(s.reward == -1.0);
    CHECK(info_of(env, "loss") == 1.0);
    CHECK(info_of(env, "illegal_move") == 0.0);
    CHECK(env.position().moves_played == 6);
    CHECK(env.position().cells[6] == 2);
  }
  SECTION("an illegal move ends the game with -1 (TerminateIllegalWrapper)") {
    ConnectFourEnv::Config config;
    config.learner_side = "first";
    config.opponent = "minimax";
    config.minimax_depth = 1;  // no win in sight: its lowest column, 0, like the learner
    config.minimax_ties = "first";
    ConnectFourEnv env(config);
    Vec obs(84);
    env.reset(3, obs);
    for (int i = 0; i < 3; ++i) CHECK(act(env, 0, obs).reward == 0.0);  // column 0 is full
    CHECK(mask_of(env, 7) == Vec{0, 1, 1, 1, 1, 1, 1});
    const StepResult s = act(env, 0, obs);
    CHECK(s.terminated);
    CHECK(s.reward == -1.0);
    CHECK(info_of(env, "illegal_move") == 1.0);
    CHECK(info_of(env, "loss") == 1.0);
    CHECK(mask_of(env, 7) == Vec(7, 0.0f));
    CHECK_THROWS_AS(act(env, 1, obs), std::logic_error);
    env.reset(std::nullopt, obs);
    CHECK_THROWS_AS(act(env, 9, obs), std::invalid_argument);  // outside Discrete(7)
  }
}

TEST_CASE("board game env: sides alternate, random sides and games follow the seed",
          "[board_games]") {
  TicTacToeEnv alternate(tic_tac_toe_config("alternate"));
  Vec obs(18);
  for (int episode = 0; episode < 4; ++episode) {
    alternate.reset(episode == 0 ? std::optional<uint64_t>(5) : std::nullopt, obs);
    CHECK(alternate.learner() == episode % 2);
  }
  // The same seed plays the same games: sides and the random opponent's moves.
  const auto games = [](uint64_t seed) {
    TicTacToeEnv env(tic_tac_toe_config("random"));
    Vec o(18);
    std::vector<int> trace;
    env.reset(seed, o);
    for (int episode = 0; episode < 20; ++episode) {
      trace.push_back(env.learner());
      StepResult s;
      do {
        int move = 0;
        while (!env.game().legal(env.position(), move)) ++move;
        s = act(env, move, o);
      } while (!s.terminated);
      for (int k = 0; k < 9; ++k) trace.push_back(env.position().cells[k]);
      env.reset(std::nullopt, o);
    }
    return trace;
  };
  CHECK(games(11) == games(11));
  CHECK(games(11) != games(12));
}

TEST_CASE("board game env: resumes exactly and refuses a bad saved board", "[board_games]") {
  ConnectFourEnv::Config config;
  config.learner_side = "random";
  config.opponent = "minimax";
  ConnectFourEnv env(config);
  CHECK(check_env(env, 0, 300).empty());
  Vec obs(84), a(84), b(84);
  env.reset(9, obs);
  for (int move : {3, 3, 2}) act(env, move, obs);
  TensorMap tensors;
  StateWriter writer(tensors);
  env.write_state(writer);
  ConnectFourEnv restored(config);
  restored.read_state(StateReader(tensors));
  // The same continuation, through game ends and resets (the RNG is part of the state).
  for (int step = 0; step < 200; ++step) {
    int move = step % 7;
    while (!env.game().legal(env.position(), move)) move = (move + 1) % 7;
    const StepResult sa = act(env, move, a);
    const StepResult sb = act(restored, move, b);
    REQUIRE(a == b);
    REQUIRE(sa.reward == sb.reward);
    REQUIRE(sa.terminated == sb.terminated);
    if (sa.terminated) {
      env.reset(std::nullopt, a);
      restored.reset(std::nullopt, b);
      REQUIRE(a == b);
    }
  }
  tensors["cells"].bytes[0] = 7;  // cell 0 holds 7
  ConnectFourEnv refused(config);
  CHECK_THROWS_AS(refused.read_state(StateReader(tensors)), StateMismatch);
  tensors["cells"].bytes[0] = 0;
  tensors["moves_played"].bytes[0] = 11;  // more moves than pieces
  CHECK_THROWS_AS(refused.read_state(StateReader(tensors)), StateMismatch);
}

TEST_CASE("board game env: kwargs are checked with a did-you-mean", "[board_games]") {
  const EnvEntry* entry = builtin_registry().find_env("TicTacToe-v0");
  REQUIRE(entry != nullptr);
  CHECK_THROWS_WITH(entry->parse(ConfigNode::load_string("opponent: minmax\n", "kw.yaml")),
                    Catch::Contains("minimax"));
  CHECK_THROWS_WITH(entry->parse(ConfigNode::load_string("learner_sde: first\n", "kw.yaml")),
                    Catch::Contains("did you mean 'learner_side'"));
  CHECK_THROWS_WITH(entry->parse(ConfigNode::load_string("minimax_depth: 0\n", "kw.yaml")),
                    Catch::Contains("minimax_depth"));
  const AnyConfig parsed =
      entry->parse(ConfigNode::load_string("opponent: minimax\nlearner_side: second\n", "kw.yaml"));
  EnvPtr env = entry->make(parsed);
  auto& game_env = dynamic_cast<BoardGameEnv&>(*env);
  CHECK(game_env.opponent().name() == "minimax depth 9");
  CHECK(game_env.config().learner_side == "second");
}

TEST_CASE("board game env: draws the board", "[board_games]") {
  TicTacToeEnv env(tic_tac_toe_config("first", "minimax"));
  Vec obs(18);
  env.reset(0, obs);
  act(env, 4, obs);  // X centre; the opponent takes square 0 (top left)
  Frame frame(env.render_spec().width, env.render_spec().height);
  REQUIRE(env.render(frame));
  CHECK(frame.width() == 300);
  const Rgb cross = frame.pixel(150, 150);  // the centre of the red X
  CHECK(cross.r > 150);
  CHECK(cross.g < 100);
  const Rgb ring = frame.pixel(50 + 28, 50);  // on the O's black ring in square 0
  CHECK(ring.r < 100);
  ConnectFourEnv four;
  Vec four_obs(84);
  four.reset(0, four_obs);
  Frame board(four.render_spec().width, four.render_spec().height);
  REQUIRE(four.render(board));
  CHECK(board.pixel(2, 2).b > 150);  // the blue frame
}
