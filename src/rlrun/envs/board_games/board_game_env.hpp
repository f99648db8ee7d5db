#pragma once
// A two-player board game as a single-agent env: the learner plays one side and the opponent
// (opponent.hpp) moves inside the env for the other, as SB3 self-play setups wrap PettingZoo's
// AEC games for one agent. The rules, observation planes, masks and rewards are PettingZoo
// classic's (pettingzoo/classic/tictactoe/tictactoe.py, connect_four/connect_four.py, with the
// TerminateIllegalWrapper env() puts around them):
//
//   observation  Box(0, 1, (rows, cols, 2)) seen by the learner: plane 0 its own pieces,
//                plane 1 the opponent's (observe(agent)); float32 here, int8 in PettingZoo.
//   action       Discrete: tic-tac-toe's square, connect four's column.
//   reward       +1 when the learner's move wins, -1 when the opponent's move wins, 0 for a
//                draw and every other step.
//   illegal move the episode ends (terminated) with reward -1 (TerminateIllegalWrapper,
//                illegal_reward=-1); info illegal_move = 1.
//   info         action_mask.<a> (1 legal, 0 not; all 0 once the game is over, as PettingZoo
//                masks an agent whose turn it is not), win / draw / loss (1 for the finished
//                game's result, 0 before), illegal_move, learner_first (1 when the learner
//                moved first this episode).
//
// When the learner plays second, reset() lets the opponent make the first move. The opponent's
// randomness (and learner_side: random) draws from the env's own Rng, so an episode is a
// function of the seed. With `opponent: self_play` each episode's opponent is a policy sampled
// at reset() from the pool handed over by set_policy_pool (env/policy_pool.hpp; the trainer's
// self_play section fills it); without a pool, or before its first snapshot, it is random.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/env/policy_pool.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/board_games/board_game.hpp"
#include "rlrun/envs/board_games/board_game_config.hpp"
#include "rlrun/envs/board_games/opponent.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun::board_games {

// The opponent a config names (random, or minimax with its depth and tie rule).
std::unique_ptr<const Opponent> make_opponent(const BoardGameConfig& config);

class BoardGameEnv : public Env, public PlaysAgainstPool {
 public:
  BoardGameEnv(std::unique_ptr<const BoardGame> game, const BoardGameConfig& config);

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return game_->name(); }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override;
  bool render(Frame& frame) const override;

  const BoardGame& game() const { return *game_; }
  const BoardPosition& position() const { return position_; }
  const Opponent& opponent() const { return *opponent_; }
  const BoardGameConfig& config() const { return config_; }
  int learner() const { return learner_; }  // 0: the learner moves first
  // Replaces the opponent (evaluation against another player); takes effect at its next move.
  void set_opponent(std::unique_ptr<const Opponent> opponent);
  // The opponent of the current episode: a pool snapshot under self_play, else opponent().
  const Opponent& episode_opponent() const;

  void set_policy_pool(std::shared_ptr<const PolicyPool> pool) override { pool_ = std::move(pool); }
  bool wants_policy_pool() const override { return config_.opponent == "self_play"; }
  int64_t pool_snapshot_in_use() const override { return pool_snapshot_id_; }

 private:
  int choose_learner_side();
  void choose_pool_opponent();
  // The snapshot a restored state names, once the pool that holds it is there.
  void resolve_pool_opponent();
  void opponent_moves();
  // The learner's reward for the position's outcome (0 while the game goes on).
  double learner_reward() const;
  bool ended() const { return position_.over() || ended_by_illegal_move_; }
  void write_info();
  void write_observation(std::span<float> obs) const;

  std::unique_ptr<const BoardGame> game_;
  BoardGameConfig config_;
  std::unique_ptr<const Opponent> opponent_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;
  std::vector<int> key_masks_;  // indices of action_mask.<a>
  int key_win_ = 0, key_draw_ = 0, key_loss_ = 0, key_illegal_ = 0, key_learner_first_ = 0;

  bool has_state_ = false;
  BoardPosition position_;
  int learner_ = 0;
  int64_t episodes_ = 0;  // resets since the last seeded one (learner_side: alternate)
  bool ended_by_illegal_move_ = false;

  std::shared_ptr<const PolicyPool> pool_;
  std::unique_ptr<const Opponent> pool_opponent_;  // this episode's snapshot (self_play)
  int64_t pool_snapshot_id_ = -1;                  // its id; -1: none (random stands in)
};

}  // namespace rlrun::board_games
