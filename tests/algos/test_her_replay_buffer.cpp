// algos/common/her_replay_buffer: SB3's HerReplayBuffer semantics on hand-made episodes. A goal
// env whose achieved goal is the step count makes every relabelled goal say where it came from:
// after step t of an episode (position t -> t + 1) the `future` goal must be in [t + 1, L], the
// `final` one L, an `episode` one in [1, L]; rewards are recomputed with the env's
// compute_reward; unfinished or overwritten episodes are never sampled; timeouts bootstrap.
#include <catch2/catch.hpp>

#include <map>
#include <memory>
#include <set>

#include "rlrun/algos/common/her_replay_buffer.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/env_base.hpp"

using namespace rlrun;

namespace {

// Dict obs (sorted keys): achieved_goal = position (0, 1, 2, ... within an episode),
// desired_goal = 100 (never reached), observation = [env marker, episode number]. An episode is
// `length` steps, terminated or truncated. Reward -1 unless |achieved - desired| < 0.5.
class LineGoalEnv : public EnvBase, public GoalEnv {
 public:
  LineGoalEnv(int marker, int length, bool terminate)
      : marker_(marker), length_(length), terminate_(terminate) {
    observation_space_ = Space::dict({{"achieved_goal", Space::box(-1e6f, 1e6f, {1})},
                                      {"desired_goal", Space::box(-1e6f, 1e6f, {1})},
                                      {"observation", Space::box(-1e6f, 1e6f, {2})}});
    action_space_ = Space::box(-1.0f, 1.0f, {1});
    id_ = "LineGoal-v0";
  }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    position_ = 0;
    ++episode_;
    write(obs);
  }
  StepResult step(std::span<const float>, std::span<float> obs) override {
    ++position_;
    write(obs);
    const bool end = position_ >= length_;
    return {-1.0, end && terminate_, end && !terminate_};
  }
  void compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                      const Eigen::Ref<const Eigen::MatrixXf>& desired,
                      Eigen::Ref<Eigen::RowVectorXf> rewards) const override {
    for (Eigen::Index j = 0; j < achieved.cols(); ++j)
      rewards(j) = std::abs(achieved(0, j) - desired(0, j)) < 0.5f ? 0.0f : -1.0f;
  }

 private:
  void write(std::span<float> obs) const {
    obs[0] = static_cast<float>(position_);  // achieved_goal
    obs[1] = 100.0f;                         // desired_goal
    obs[2] = static_cast<float>(marker_);    // observation
    obs[3] = static_cast<float>(episode_);
  }
  int marker_, length_;
  bool terminate_;
  int position_ = 0, episode_ = 0;
};

// Obs layout: 0 achieved, 1 desired, 2 marker, 3 episode.
constexpr int kAchieved = 0, kDesired = 1, kMarker = 2, kEpisode = 3;

struct Setup {
  VecEnv env;
  std::unique_ptr<HerReplayBuffer> buffer;
  const LineGoalEnv* goals;

  Setup(std::vector<int> lengths, int64_t size, GoalSelection selection, bool terminate = false,
        int n_sampled_goal = 4)
      : env(make(lengths, terminate)) {
    goals = dynamic_cast<const LineGoalEnv*>(goal_env_of(env.env(0)));
    buffer = std::make_unique<HerReplayBuffer>(size, env.num_envs(), env.observation_space(), 1,
                                               goals, n_sampled_goal, selection);
    env.reset();
  }
  static std::vector<EnvPtr> make(const std::vector<int>& lengths, bool terminate) {
    std::vector<EnvPtr> envs;
    for (size_t e = 0; e < lengths.size(); ++e)
      envs.push_back(std::make_unique<LineGoalEnv>(static_cast<int>(e), lengths[e], terminate));
    return envs;
  }
  void steps(int n) {
    const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, env.num_envs());
    for (int t = 0; t < n; ++t) {
      const Eigen::MatrixXf obs = env.obs();
      env.step(actions);
      buffer->add(obs, actions, env);
    }
  }
};

}  // namespace

TEST_CASE(
    "HER: future goals come from the transition onwards, final from the end, episode from anywhere",
    "[algos][her]") {
  constexpr int kLength = 5;
  for (const auto selection :
       {GoalSelection::kFuture, GoalSelection::kFinal, GoalSelection::kEpisode}) {
    Setup s({kLength}, 100, selection);
    s.steps(4 * kLength);
    Rng rng(7);
    ReplayBatch batch;
    s.buffer->sample(2000, rng, batch);
    const int virtual_count = static_cast<int>(0.8 * 2000);  // n_sampled_goal 4: her_ratio 0.8
    CHECK(s.buffer->her_ratio() == Approx(0.8));
    std::set<int> goals_seen;
    std::set<std::pair<int, int>> future_pairs;
    for (int j = 0; j < 2000; ++j) {
      const float t = batch.obs(kAchieved, j);  // position before the step
      const float g = batch.obs(kDesired, j);
      CHECK(batch.next_obs(kAchieved, j) == t + 1);
      CHECK(batch.next_obs(kDesired, j) == g);  // the same goal in obs and next_obs
      CHECK(batch.dones(j) == 0.0f);            // truncated: bootstrap
      if (j >= virtual_count) {                 // real: as stored
        CHECK(g == 100.0f);
        CHECK(batch.rewards(j) == -1.0f);
        continue;
      }
      goals_seen.insert(static_cast<int>(g));
      // The reward of the relabelled transition: compute_reward(next achieved, new goal).
      CHECK(batch.rewards(j) == (g == t + 1 ? 0.0f : -1.0f));
      if (selection == GoalSelection::kFuture) {
        CHECK(g >= t + 1);  // inclusive: the transition's own next achieved goal may be drawn
        CHECK(g <= kLength);
        future_pairs.insert({static_cast<int>(t), static_cast<int>(g)});
      } else if (selection == GoalSelection::kFinal) {
        CHECK(g == kLength);
      } else {
        CHECK(g >= 1);
        CHECK(g <= kLength);
      }
    }
    if (selection == GoalSelection::kFuture)
      CHECK(future_pairs.size() == 15);  // every (t, g >= t+1)
    if (selection == GoalSelection::kFinal) CHECK(goals_seen == std::set<int>{kLength});
    if (selection == GoalSelection::kEpisode) CHECK(goals_seen == std::set<int>{1, 2, 3, 4, 5});
  }
}

TEST_CASE("HER: unfinished and overwritten episodes are not sampled, the buffer wraps",
          "[algos][her]") {
  // 12 slots, episodes of 5: after 3 episodes + 2 steps the third episode wrapped (slots 10,
  // 11, 0, 1, 2), the first lost its start (slots 3, 4 left: not sampled), the fourth is
  // unfinished.
  Setup s({5}, 12, GoalSelection::kFuture);
  s.steps(17);
  CHECK(s.buffer->valid_transitions() == 10);  // episodes 2 and 3
  Rng rng(3);
  ReplayBatch batch;
  s.buffer->sample(3000, rng, batch);
  std::map<int, int> by_episode;
  for (int j = 0; j < 3000; ++j) {
    ++by_episode[static_cast<int>(batch.obs(kEpisode, j))];
    if (j < 2400) {  // virtual: goals from the same, intact episode
      CHECK(batch.obs(kDesired, j) >= batch.obs(kAchieved, j) + 1);
      CHECK(batch.obs(kDesired, j) <= 5);
    }
  }
  CHECK(by_episode.size() == 2);
  CHECK(by_episode.count(2) == 1);
  CHECK(by_episode.count(3) == 1);
  CHECK(by_episode[2] > 1200);  // uniform over the 10 valid transitions
  CHECK(by_episode[3] > 1200);
}

TEST_CASE("HER: several envs keep their own episodes, terminations do not bootstrap",
          "[algos][her]") {
  Setup s({3, 5}, 60, GoalSelection::kEpisode, /*terminate=*/true);
  s.steps(15);
  Rng rng(11);
  ReplayBatch batch;
  s.buffer->sample(2000, rng, batch);
  std::set<int> markers;
  for (int j = 0; j < 2000; ++j) {
    const int env = static_cast<int>(batch.obs(kMarker, j));
    markers.insert(env);
    const int length = env == 0 ? 3 : 5;
    if (j < 1600) CHECK(batch.obs(kDesired, j) <= length);  // a goal of the same env's episode
    // The episode's last transition is terminal (terminated): no bootstrap; others bootstrap.
    CHECK(batch.dones(j) == (batch.next_obs(kAchieved, j) == length ? 1.0f : 0.0f));
  }
  CHECK(markers == std::set<int>{0, 1});
}

TEST_CASE("HER: n_sampled_goal 0 samples real transitions only, errors, exact state round trip",
          "[algos][her]") {
  {
    Setup s({4}, 40, GoalSelection::kFuture, false, /*n_sampled_goal=*/0);
    s.steps(8);
    Rng rng(1);
    ReplayBatch batch;
    s.buffer->sample(100, rng, batch);
    CHECK((batch.obs.row(kDesired).array() == 100.0f).all());
  }
  Setup s({4}, 40, GoalSelection::kFuture);
  Rng rng(1);
  ReplayBatch batch;
  s.steps(3);  // no episode has ended yet
  CHECK_THROWS_WITH(s.buffer->sample(8, rng, batch), Catch::Contains("learning_starts"));
  CHECK_THROWS_AS(parse_goal_selection("random"), std::invalid_argument);
  CHECK(parse_goal_selection("final") == GoalSelection::kFinal);
  const LineGoalEnv goals(0, 3, false);
  CHECK_THROWS_WITH(
      HerReplayBuffer(10, 1, Space::box(0.0f, 1.0f, {3}), 1, &goals, 4, GoalSelection::kFuture),
      Catch::Contains("Dict observation"));
  CHECK_THROWS_WITH(HerReplayBuffer(10, 1,
                                    Space::dict({{"achieved_goal", Space::box(0.0f, 1.0f, {2})},
                                                 {"observation", Space::box(0.0f, 1.0f, {2})}}),
                                    1, &goals, 4, GoalSelection::kFuture),
                    Catch::Contains("desired_goal"));

  // Resume: a restored buffer samples exactly what the original samples.
  s.steps(10);
  TensorMap tensors;
  s.buffer->write_state(StateWriter(tensors, "buffer/"));
  HerReplayBuffer restored(40, 1, s.env.observation_space(), 1, s.goals, 4, GoalSelection::kFuture);
  restored.read_state(StateReader(tensors, "buffer/"));
  Rng a(9), b(9);
  ReplayBatch x, y;
  s.buffer->sample(64, a, x);
  restored.sample(64, b, y);
  CHECK(x.obs == y.obs);
  CHECK(x.next_obs == y.next_obs);
  CHECK(x.rewards == y.rewards);
  CHECK(x.dones == y.dones);
}

namespace {

// The buffer's state with `edit(tensors)` applied, restored into a fresh buffer like `s`'s.
template <class Edit>
void restore_edited(const Setup& s, int64_t size, Edit edit) {
  TensorMap tensors;
  s.buffer->write_state(StateWriter(tensors, "buffer/"));
  edit(tensors);
  HerReplayBuffer restored(size, s.env.num_envs(), s.env.observation_space(), 1, s.goals, 4,
                           GoalSelection::kFuture);
  restored.read_state(StateReader(tensors, "buffer/"));
}

int64_t& entry(TensorMap& tensors, const std::string& key, size_t index) {
  return tensors.at("buffer/her/" + key).data<int64_t>()[index];
}

}  // namespace

TEST_CASE("HER: restored episode bookkeeping must be what add() writes (no unwritten slots)",
          "[algos][her]") {
  // States the buffer writes itself are accepted: not full, wrapped, an episode longer than
  // the buffer, one exactly as long, two envs.
  for (const auto& [lengths, size, steps] :
       std::vector<std::tuple<std::vector<int>, int64_t, int>>{{{4}, 40, 10},
                                                               {{5}, 12, 17},
                                                               {{15}, 10, 17},
                                                               {{10}, 10, 10},
                                                               {{10}, 10, 23},
                                                               {{3, 5}, 60, 15},
                                                               {{3, 5}, 16, 45}}) {
    Setup s(lengths, size, GoalSelection::kFuture);
    s.steps(steps);
    INFO(size << " slots, " << steps << " steps");
    CHECK_NOTHROW(restore_edited(s, size, [](TensorMap&) {}));
  }

  // 40 slots, episodes of 4 after 10 steps: [0, 4) and [4, 8) finished, 8 and 9 unfinished,
  // the write position at 10.
  Setup s({4}, 40, GoalSelection::kFuture);
  s.steps(10);
  const auto refused = [&](auto edit, const std::string& why) {
    CHECK_THROWS_WITH(restore_edited(s, 40, edit), Catch::Contains(why));
  };
  // The case: the unfinished episode "starts" at a slot never written (its goals would
  // be read from uninitialised memory once it ends).
  refused([](TensorMap& t) { entry(t, "current_ep_start", 0) = 39; },
          "the unfinished episode starts at slot 39, but 10 of 40 slots are written");
  refused([](TensorMap& t) { entry(t, "current_ep_start", 0) = 4; },
          "slot 4 of the unfinished episode from slot 4 is recorded as another episode");
  refused([](TensorMap& t) { entry(t, "current_ep_start", 0) = 7; },
          "is recorded as another episode");
  refused([](TensorMap& t) { entry(t, "ep_length", 0) = 12; }, "outside the 10 written slots");
  refused(
      [](TensorMap& t) {
        entry(t, "ep_length", 20) = 1;
        entry(t, "ep_start", 20) = 20;
      },
      "slot 20 records an episode of 1 from slot 20, outside the 10 written slots");
  refused([](TensorMap& t) { entry(t, "ep_start", 2) = 1; },
          "slot 0 records an episode of 4 from slot 0, but its slot 2 records another");
  refused([](TensorMap& t) { entry(t, "ep_length", 3) = 3; }, "but its slot 3 records another");
  refused(
      [](TensorMap& t) {
        entry(t, "ep_start", 5) = 3;
        entry(t, "ep_length", 5) = 1;
      },
      "slot 4 records an episode of 4 from slot 4, but its slot 5 records another");
  refused([](TensorMap& t) { entry(t, "ep_length", 1) = 0; },
          "slot 0 records an episode of 4 from slot 0, but its slot 1 records another");
  refused(
      [](TensorMap& t) {
        entry(t, "ep_length", 9) = 0;
        entry(t, "ep_start", 9) = 0;
      },
      "slot 9 of the unfinished episode from slot 8 is recorded as another episode");
  refused([](TensorMap& t) { entry(t, "ep_length", 20) = -1; },
          "slot 20 records an episode of -1 from slot 0, outside the 10 written slots");
  refused([](TensorMap& t) { t.at("buffer/full").data<int64_t>()[0] = 2; }, "'buffer/full' is 2");

  // Full: the slot at the write position, when valid, starts its episode (the oldest data).
  Setup wrapped({5}, 12, GoalSelection::kFuture);
  wrapped.steps(17);  // pos 5: [5, 10) the oldest episode, [10, 15) wrapped, slots 3, 4 open
  CHECK_THROWS_WITH(restore_edited(wrapped, 12,
                                   [](TensorMap& t) {
                                     entry(t, "current_ep_start", 0) = 5;  // no unfinished episode
                                     for (size_t slot = 3; slot < 8; ++slot) {
                                       entry(t, "ep_start", slot) = 3;
                                       entry(t, "ep_length", slot) = 5;
                                     }
                                   }),
                    Catch::Contains("slot 5 records an episode of 5 from slot 3, but the write "
                                    "position is inside it"));
  // Slot 0 of the episode that wrapped (slots 10, 11, 0, 1, 2), said to start at slot 1.
  CHECK_THROWS_WITH(
      restore_edited(wrapped, 12, [](TensorMap& t) { entry(t, "ep_start", 0) = 1; }),
      Catch::Contains("slot 0 records an episode of 5 from slot 1 that does not cover it"));
}
