#include "rlrun/envs/board_games/board_game_env.hpp"

#include <array>
#include <limits>
#include <stdexcept>

#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/discrete_action.hpp"
#include "rlrun/envs/board_games/minimax_opponent.hpp"
#include "rlrun/envs/board_games/policy_opponent.hpp"
#include "rlrun/envs/board_games/random_opponent.hpp"

namespace rlrun::board_games {

std::unique_ptr<const Opponent> make_opponent(const BoardGameConfig& config) {
  // self_play: random until a pool snapshot plays (BoardGameEnv::choose_pool_opponent).
  if (config.opponent == "random" || config.opponent == "self_play")
    return std::make_unique<RandomOpponent>();
  if (config.opponent == "minimax")
    return std::make_unique<MinimaxOpponent>(
        config.minimax_depth, config.minimax_ties == "first" ? MinimaxOpponent::Ties::kFirst
                                                             : MinimaxOpponent::Ties::kRandom);
  throw std::invalid_argument("unknown opponent '" + config.opponent +
                              "' (random, minimax or self_play)");
}

BoardGameEnv::BoardGameEnv(std::unique_ptr<const BoardGame> game, const BoardGameConfig& config)
    : game_(std::move(game)),
      config_(config),
      opponent_(make_opponent(config)),
      observation_space_(Space::box(0.0f, 1.0f, game_->observation_shape())),
      action_space_(Space::discrete(game_->num_actions())) {
  for (int a = 0; a < game_->num_actions(); ++a)
    key_masks_.push_back(info_.add_key(action_mask_key(a)));
  key_win_ = info_.add_key("win");
  key_draw_ = info_.add_key("draw");
  key_loss_ = info_.add_key("loss");
  key_illegal_ = info_.add_key("illegal_move");
  key_learner_first_ = info_.add_key("learner_first");
  position_ = game_->start();
}

void BoardGameEnv::set_opponent(std::unique_ptr<const Opponent> opponent) {
  if (!opponent) throw std::invalid_argument(id() + ": set_opponent needs an opponent");
  opponent_ = std::move(opponent);
}

int BoardGameEnv::choose_learner_side() {
  // The coin of learner_side: random is drawn whatever the setting, so the opponents' draws
  // after it are the same stream for every learner_side.
  const int coin = static_cast<int>(seeding_.rng().below(2));
  if (config_.learner_side == "first") return 0;
  if (config_.learner_side == "second") return 1;
  if (config_.learner_side == "alternate") return static_cast<int>(episodes_ % 2);
  return coin;  // random
}

const Opponent& BoardGameEnv::episode_opponent() const {
  return pool_opponent_ ? *pool_opponent_ : *opponent_;
}

void BoardGameEnv::choose_pool_opponent() {
  pool_opponent_.reset();
  pool_snapshot_id_ = -1;
  if (!wants_policy_pool() || !pool_ || pool_->empty()) return;
  const PolicySnapshot& snapshot = pool_->sample(seeding_.rng());
  pool_opponent_ = std::make_unique<PolicyOpponent>(*game_, snapshot.policy, snapshot.id,
                                                    config_.self_play_deterministic);
  pool_snapshot_id_ = snapshot.id;
}

void BoardGameEnv::resolve_pool_opponent() {
  if (pool_snapshot_id_ < 0 || pool_opponent_) return;
  const PolicySnapshot* snapshot = pool_ ? pool_->find(pool_snapshot_id_) : nullptr;
  if (!snapshot)
    throw std::runtime_error(id() + ": the saved game's opponent, self-play snapshot " +
                             std::to_string(pool_snapshot_id_) + ", is not in the policy pool");
  pool_opponent_ = std::make_unique<PolicyOpponent>(*game_, snapshot->policy, snapshot->id,
                                                    config_.self_play_deterministic);
}

void BoardGameEnv::opponent_moves() {
  if (position_.over() || position_.to_move == learner_) return;
  Rng& rng = seeding_.rng();
  const bool random_move =
      config_.opponent_random_moves > 0 && rng.uniform() < config_.opponent_random_moves;
  resolve_pool_opponent();
  const Opponent& opponent = episode_opponent();
  const int action = random_move ? RandomOpponent().choose(*game_, position_, rng)
                                 : opponent.choose(*game_, position_, rng);
  if (!game_->legal(position_, action))
    throw std::logic_error(id() + ": the " + opponent.name() + " opponent chose illegal move " +
                           std::to_string(action));
  game_->play(position_, action);
}

void BoardGameEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  // Gymnasium seeding (gymnasium/core.py Env.reset; rlrun/env_seeding.hpp), as every rlrun env.
  seeding_.on_reset(seed);
  // A seed restarts the alternation too, so reset(seed) is deterministic (Gymnasium's rule).
  if (seed) episodes_ = 0;
  position_ = game_->start();
  learner_ = choose_learner_side();
  choose_pool_opponent();
  ++episodes_;
  ended_by_illegal_move_ = false;
  has_state_ = true;
  opponent_moves();  // the opponent opens when the learner plays second
  write_info();
  write_observation(obs);
}

double BoardGameEnv::learner_reward() const {
  if (position_.outcome == win_for(learner_)) return 1.0;
  if (position_.outcome == win_for(1 - learner_)) return -1.0;
  return 0.0;
}

StepResult BoardGameEnv::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_ || ended())
    throw std::logic_error(id() + ": call reset() before step() (the game is over)");
  const int move = checked_discrete_action(action_space_, action, id());
  StepResult result;
  if (!game_->legal(position_, move)) {
    // TerminateIllegalWrapper(illegal_reward=-1): the game ends, the mover gets -1.
    ended_by_illegal_move_ = true;
    result.reward = -1.0;
    result.terminated = true;
  } else {
    game_->play(position_, move);
    opponent_moves();
    result.reward = learner_reward();
    result.terminated = position_.over();
  }
  write_info();
  write_observation(obs);
  return result;
}

void BoardGameEnv::write_info() {
  info_.clear();
  std::array<float, kMaxCells> mask{};  // a game has at most one action per cell
  const std::span<float> legal(mask.data(), static_cast<size_t>(game_->num_actions()));
  game_->write_mask(position_, legal);
  for (size_t a = 0; a < key_masks_.size(); ++a)
    info_.set(key_masks_[a], ended_by_illegal_move_ ? 0.0 : legal[a]);
  const double reward = ended_by_illegal_move_ ? -1.0 : learner_reward();
  const bool over = ended();
  info_.set(key_win_, over && reward > 0 ? 1.0 : 0.0);
  info_.set(key_draw_, over && reward == 0 ? 1.0 : 0.0);
  info_.set(key_loss_, over && reward < 0 ? 1.0 : 0.0);
  info_.set(key_illegal_, ended_by_illegal_move_ ? 1.0 : 0.0);
  info_.set(key_learner_first_, learner_ == 0 ? 1.0 : 0.0);
}

void BoardGameEnv::write_observation(std::span<float> obs) const {
  game_->write_planes(position_, learner_, obs);
}

void BoardGameEnv::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  std::vector<int64_t> cells(position_.cells.begin(), position_.cells.begin() + game_->num_cells());
  out.put_vector("cells", cells);
  out.put_int("to_move", position_.to_move);
  out.put_int("moves_played", position_.moves_played);
  out.put_int("outcome", static_cast<int64_t>(position_.outcome));
  out.put_int("learner", learner_);
  out.put_int("episodes", episodes_);
  out.put_bool("ended_by_illegal_move", ended_by_illegal_move_);
  out.put_int("pool_snapshot", pool_snapshot_id_);
}

void BoardGameEnv::read_state(const StateReader& in) {
  seeding_.read_state(in);
  BoardPosition position;
  const std::vector<int64_t> cells = in.get_span<int64_t>("cells", game_->num_cells());
  for (size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] < 0 || cells[i] > 2)
      throw StateMismatch(id() + ": a board cell holds " + std::to_string(cells[i]) +
                          ", not 0, 1 or 2");
    position.cells[i] = static_cast<int8_t>(cells[i]);
  }
  position.to_move = static_cast<int>(in.get_int_in("to_move", 0, 1));
  position.moves_played = static_cast<int>(in.get_int_in("moves_played", 0, game_->num_cells()));
  position.outcome = static_cast<Outcome>(in.get_int_in("outcome", 0, 3));
  if (!game_->plausible(position))
    throw StateMismatch(id() + ": the saved board does not match its move count and turn");
  const int learner = static_cast<int>(in.get_int_in("learner", 0, 1));
  const bool illegal = in.get_bool("ended_by_illegal_move");
  // Between steps of a game that goes on it is always the learner's turn.
  if (!position.over() && !illegal && position.moves_played > 0 && position.to_move != learner)
    throw StateMismatch(id() + ": the saved game waits for the opponent's move");
  has_state_ = in.get_bool("has_state");
  position_ = position;
  learner_ = learner;
  episodes_ = in.get_int_in("episodes", 0, std::numeric_limits<int64_t>::max());
  ended_by_illegal_move_ = illegal;
  // The snapshot is looked up when the opponent next moves: a resumed run restores the pool
  // (the self_play callback's state) after the envs.
  pool_opponent_.reset();
  pool_snapshot_id_ = in.get_int_in("pool_snapshot", -1, std::numeric_limits<int64_t>::max());
  write_info();
}

}  // namespace rlrun::board_games
