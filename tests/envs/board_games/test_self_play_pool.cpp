// Self-play's pieces below the trainer: the policy pool's opponent sampling (latest with
// probability p, else an older snapshot uniformly; capacity; retired snapshots), a frozen
// policy as the opponent (legal moves only, from its own side), the env's self_play opponent
// per episode and its exact resume.
#include <catch2/catch.hpp>
#include <map>
#include <vector>

#include "rlrun/env/policy_pool.hpp"
#include "rlrun/envs/board_games/board_game_envs.hpp"
#include "rlrun/envs/board_games/policy_opponent.hpp"

using namespace rlrun;
using namespace rlrun::board_games;

namespace {

using Vec = std::vector<float>;

// Prefers action `favourite`, then lower actions; records the observations it saw.
class FavouritePolicy : public FrozenPolicy {
 public:
  FavouritePolicy(int actions, int favourite) : actions_(actions), favourite_(favourite) {}
  int num_actions() const override { return actions_; }
  void logits(std::span<const float> obs, std::span<float> out) const override {
    last_obs = Vec(obs.begin(), obs.end());
    for (int a = 0; a < actions_; ++a) out[a] = a == favourite_ ? 10.0f : -static_cast<float>(a);
  }
  mutable Vec last_obs;

 private:
  int actions_, favourite_;
};

PolicySnapshot snapshot(int64_t id, int favourite, int actions = 9) {
  return {id, id * 100, std::make_shared<FavouritePolicy>(actions, favourite)};
}

StepResult act(Env& env, int action, Vec& obs) {
  const float a = static_cast<float>(action);
  return env.step({&a, 1}, obs);
}

}  // namespace

TEST_CASE("policy pool: capacity, ids and the latest-or-older sampling", "[board_games]") {
  CHECK_THROWS_AS(PolicyPool(0, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(PolicyPool(3, 1.5), std::invalid_argument);
  PolicyPool pool(3, 0.25);
  Rng rng(1);
  CHECK_THROWS_AS(pool.sample(rng), std::logic_error);
  pool.add(snapshot(0, 0));
  CHECK(pool.sample(rng).id == 0);  // the only one
  for (int id = 1; id < 5; ++id) pool.add(snapshot(id, 0));
  CHECK_THROWS_AS(pool.add(snapshot(4, 0)), std::invalid_argument);
  REQUIRE(pool.snapshots().size() == 3);  // 2, 3, 4: the oldest dropped
  CHECK(pool.snapshots().front().id == 2);
  CHECK(pool.find(1) == nullptr);
  pool.add_retired(snapshot(1, 0));
  CHECK(pool.find(1) != nullptr);
  std::map<int64_t, int> counts;
  const int draws = 40000;
  for (int i = 0; i < draws; ++i) ++counts[pool.sample(rng).id];
  CHECK(counts.count(1) == 0);  // retired snapshots are not sampled
  CHECK(counts[4] / double(draws) == Approx(0.25).margin(0.015));
  CHECK(counts[2] / double(draws) == Approx(0.375).margin(0.015));
  CHECK(counts[3] / double(draws) == Approx(0.375).margin(0.015));
}

TEST_CASE("policy opponent: plays its best legal move from its own side", "[board_games]") {
  TicTacToe game;
  auto policy = std::make_shared<FavouritePolicy>(9, 4);
  const PolicyOpponent best(game, policy, 7, /*deterministic=*/true);
  CHECK(best.name() == "policy snapshot 7");
  BoardPosition position = game.start();
  Rng rng(0);
  game.play(position, 0);  // X at 0; the opponent (O) moves
  CHECK(best.choose(game, position, rng) == 4);
  // It saw the board from its side: its own pieces (none) in plane 0, X's in plane 1.
  CHECK(policy->last_obs[0] == 0.0f);
  CHECK(policy->last_obs[1] == 1.0f);
  game.play(position, 4);
  game.play(position, 8);
  CHECK(best.choose(game, position, rng) == 1);  // 4 is taken: the next best legal one
  CHECK_THROWS_AS(PolicyOpponent(game, std::make_shared<FavouritePolicy>(7, 0), 0, true),
                  std::invalid_argument);
  // Sampling puts almost all weight on the favourite (logit 10 against <= 0).
  const PolicyOpponent sampler(game, policy, 7, /*deterministic=*/false);
  int favourite = 0;
  for (int i = 0; i < 200; ++i) favourite += sampler.choose(game, game.start(), rng) == 4;
  CHECK(favourite > 190);
}

TEST_CASE("board game env: self_play opponents come from the pool per episode", "[board_games]") {
  TicTacToeEnv::Config config;
  config.opponent = "self_play";
  config.learner_side = "second";
  config.self_play_deterministic = true;
  TicTacToeEnv env(config);
  CHECK(env.wants_policy_pool());
  Vec obs(18);
  env.reset(2, obs);
  CHECK(env.episode_opponent().name() == "random");  // no pool yet
  CHECK(env.pool_snapshot_in_use() == -1);
  auto pool = std::make_shared<PolicyPool>(4, 1.0);  // always the latest
  pool->add(snapshot(0, 6));
  env.set_policy_pool(pool);
  env.reset(std::nullopt, obs);
  CHECK(env.pool_snapshot_in_use() == 0);
  CHECK(obs[2 * 6 + 1] == 1.0f);  // the snapshot opened at square 6
  // A later snapshot is played from the next episode on; this game keeps its opponent.
  pool->add(snapshot(1, 2));
  act(env, 4, obs);
  CHECK(env.position().cells[0] == 1);  // snapshot 0 (the first player) next: square 0
  // Resume: the saved game names snapshot 0, found again in the restored env's pool.
  TensorMap tensors;
  StateWriter writer(tensors);
  env.write_state(writer);
  TicTacToeEnv restored(config);
  restored.read_state(StateReader(tensors));
  Vec a(18), b(18);
  restored.set_policy_pool(pool);
  REQUIRE(act(env, 8, a).reward == act(restored, 8, b).reward);
  CHECK(a == b);
  // A pool without that snapshot: the restored game cannot go on, and says why.
  TicTacToeEnv orphan(config);
  orphan.read_state(StateReader(tensors));
  auto other = std::make_shared<PolicyPool>(4, 1.0);
  other->add(snapshot(5, 2));
  orphan.set_policy_pool(other);
  CHECK_THROWS_WITH(act(orphan, 8, b), Catch::Contains("self-play snapshot 0"));
  env.reset(std::nullopt, obs);
  CHECK(env.pool_snapshot_in_use() == 1);
  CHECK(obs[2 * 2 + 1] == 1.0f);
}
